"""rmot.compiler: the compiler proper and the application on top: the top layer, the one
folder that may import all the others (pyproject's layer contract, `lint-imports`).

Where things are:

    passes/     AST + cell -> IR, one pass a module (pipeline.py lists them in order)
    plan/       IR -> Plan: IK branch per target, blends, time-optimal timing per task
    design/     cell design studies joining the planner and the verifier: reach and
                singularity maps, robot comparison, base placement, dynamics figures
    driver      frontend (file -> checked IR, default_cell.rmot when a program has no cell),
                pipeline (the passes in order), plan_cache (content-addressed Plans),
                plan_codec (a Plan as JSON + arrays), ir_dump (`rmot ir`)
    cli/        click commands, exit codes, the only file I/O, and the caches of the stages
                they run (load, verify, free paths)
    lsp/        the language server (`rmot lsp`)

Below it: sim/ (the physical world: robots, kinematics, collision, verification, rendering)
and backends/ (the vendor printers), which never import each other; lang/ (the language and
the vocabulary every stage reads: AST, IR, plan types, codes, registries) under both.

Each stage is a function over immutable values (lang/record.py); a value is decided once, on
the IR or the Plan, and every consumer reads it from there."""
