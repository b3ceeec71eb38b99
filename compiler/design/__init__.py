"""Cell design studies: reach and singularity maps, robot comparison, base placement, dynamics.

These join the planner and the verifier (so they live in compiler/, above both):

    reach.reach_map(robot, ...)           -> ReachMap   (which points the TCP reaches, how well)
    metrics.plan_metrics(plan, report)    -> per-task margins, manipulability, torque figures
    place.place(program, robot, region)   -> Placement  (a verified base pose, best by objective)

The CLI modules (compiler/cli/reach_cmd.py, compare_cmd.py, place_cmd.py) only parse options,
call these and write files.
"""

from __future__ import annotations
