"""The robot library and kinematics: FK, Jacobians, closed-form and numeric IK, branches.

    from rmot.sim.robots import load_robot, list_robots
    r = load_robot("abb_irb120")          # a library name, or a path to a URDF file
    r.fk(q) -> (4,4); r.ik(T) -> IkResult; r.branch(q) -> ir.Config

The contract is the Robot class (robot.py: fk, fk_batch, jacobian, ik, ik_batch, branch,
limits, solids; units SI, joints in rad or m); `branches` defines the IK branches, `ik` the
statuses of an IkResult, `library` the built-in arms with the sources of their numbers.
"""

from __future__ import annotations

from rmot.sim.robots.errors import RobotError
from rmot.sim.robots.ik import IkResult, IkStatus
from rmot.sim.robots.loader import list_robots, load_robot
from rmot.sim.robots.robot import LinkSolid, Robot

__all__ = ["IkResult", "IkStatus", "LinkSolid", "Robot", "RobotError", "list_robots", "load_robot"]
