"""rmot.compiler.plan."""
