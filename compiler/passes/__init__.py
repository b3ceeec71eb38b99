"""rmot.compiler.passes."""
