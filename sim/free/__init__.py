"""`move free`: the joint-space search for a collision-free path (search.py) in the verifier's
own model of the cell (space.py), and the plan-time lowering of each `move free` into joint moves
through the via points it finds (lower.py). The command line joins it to the planner
(compiler/cli/stages.py), since the planner itself never imports the simulator."""
