"""rmot.compiler: the compiler proper (front-end passes, planner), the vocabulary every stage
reads (IR, plan types, codes, registries), the robots, and the application on top (the `rmot`
command line and the modules only it uses).

Where things are, bottom to top (the layer contract in pyproject.toml, `lint-imports`, checks
that each row imports only rows below it, with `sim` and `backends` between plan and cli):

    vocabulary  ir (the checked program, SI units), ir_tree (which instruction holds which
                bodies: the one IR walker), plan_types (the Plan: the planner's hand-off),
                codes / cache_codes (diagnostic codes), motion_kinds (tables keyed by motion
                kind are complete), model_spec (a cell's `model` robot as data), vendors (the
                one registry of --target names), atomic (the one file writer), jit (numba
                kernels that also run as plain Python)
    robots/     the robot library and kinematics: FK, Jacobians, closed-form and numeric IK,
                IK branches, dynamics (pinocchio)
    passes/     AST + cell -> IR, one pass a module (pipeline.py lists them in order)
    plan/       IR -> Plan: IK branch per target, blends, time-optimal timing per task
    (sim/ and backends/ sit here: verification and rendering; vendor printers)
    application frontend (file -> checked IR), pipeline (the passes in order), plan_cache
                (content-addressed Plans), plan_codec (a Plan as JSON + arrays), ir_dump
                (`rmot ir`), cli/ (click commands, exit codes, the only file I/O)

Each stage is a function over immutable values (lang/record.py); a value is decided once, on
the IR or the Plan, and every consumer reads it from there."""
