"""rmot.sim."""
