"""rmot.compiler.passes: the front end's passes, AST + cell -> checked ir.Program.

compiler/pipeline.py runs them in order, each returning a copy of the shared state
(state.py) with its results filled in: load_files (read and parse every file named),
lower_cell (the cell block -> ir.Cell and the cell scope; lower_model for a cell's `model`
robots, urdf_paths for the files a URDF names), scopes (the top-level names of every file,
duplicates), lower_program (one ir.Task per robot; lower_body lowers its statements: loops
with every iteration, procs inlined, modal settings via modal.py, runtime conditions via
runtime.py, joint turns via turns.py), the two proc checks of procs.py (unknown names in
procs no task calls, recursion), check_syncs (barriers pair up across tasks), assign_uids
(every instruction numbered). Shared helpers: context (scopes, the diagnostics Reporter, the
robot loader), evaluate and values (constant folding with units, all SI), limits (bounds on
numbers and on the work a program may cause)."""
