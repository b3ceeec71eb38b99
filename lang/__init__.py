"""rmot.lang."""
