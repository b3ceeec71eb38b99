"""`rmot lsp`: a Language Server Protocol server for .rmot files (application layer).

It sits beside the command line (compiler/cli) and reuses the same front end, planner,
verification and caches; it never emits vendor files.

    index.py     names declared and used in the parsed files: definitions, references
    analysis.py  one document through the front end: LSP diagnostics, the index, the IR
    planning.py  plan + verification in a separate process, cancelled when the text changes
    features.py  hover, completion, document symbols, inlay hints over an analysis
    server.py    the pygls server: documents, debouncing, publishing
"""
