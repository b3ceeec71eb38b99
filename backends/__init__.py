"""rmot.backends."""
