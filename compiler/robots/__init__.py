"""rmot.compiler.robots."""
