"""rmot.compiler."""
