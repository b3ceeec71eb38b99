"""rmot.sim.render."""
