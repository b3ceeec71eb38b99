"""What a program assumes of the controller it is loaded on: the robot's brand, and the
controller's stored tool and frame numbers.

* Brand: a program written for a controller of one brand drives that brand's arms only (KRL
  runs on a KUKA KR C4, RAPID on an ABB IRC5/OmniCore, ...). The robot library names its
  arms `<brand>_<model>` (abb_irb1600, kuka_kr16, fanuc_m20ia, ur5e, yaskawa_gp8,
  staubli_tx2_60); a library arm of another brand than the target's is warned W415 at the
  robot's declaration. URDF arms and library arms of no controller brand (puma560) are not
  judged.
* Numbers: a cell may give a tool or frame the number it has on the controller (`tool t = ...
  number 3 on r1`, `frame f = ... number 2`). Vendors that select tools and frames by number
  (Fanuc UTOOL/UFRAME, KUKA TOOL_DATA/BASE_DATA, Yaskawa tool files / user frames) then use
  that number and leave the stored data alone unless `--write-frames` is given.
"""

from __future__ import annotations

from rmot.lang import ir

__all__ = ["TARGET_BRANDS", "brand_of", "frame_number", "tool_number", "NumberedData"]

# --target -> (the brand name printed, the library-name prefixes of that brand's arms)
TARGET_BRANDS: dict[str, tuple[str, tuple[str, ...]]] = {
    "rapid": ("ABB", ("abb_",)),
    "krl": ("KUKA", ("kuka_",)),
    "fanuc": ("FANUC", ("fanuc_",)),
    "urscript": ("Universal Robots", ("ur3", "ur5", "ur10", "ur16", "ur20", "ur30")),
    "inform": ("Yaskawa", ("yaskawa_", "motoman_")),
    "val3": ("Stäubli", ("staubli_",)),
}
_OTHER = ("puma",)  # library arms no controller here drives: not judged


def brand_of(robot: ir.RobotInstance) -> str | None:
    """The controller brand of a library arm (from its name), None for URDF or unknown arms."""
    if robot.source.kind is not ir.RobotSourceKind.LIBRARY:
        return None
    ref = robot.source.ref.lower()
    if ref.startswith(_OTHER):
        return None
    return next((brand for brand, prefixes in TARGET_BRANDS.values() if ref.startswith(prefixes)), None)


def tool_number(cell: ir.Cell, robot: str, name: str | None) -> int | None:
    """The controller number the cell gives tool `name` on `robot` (None: none given)."""
    if name is None:
        return None
    return next((t.number for t in cell.tools if t.name == name and t.robot == robot), None)


def frame_number(cell: ir.Cell, name: str | None) -> int | None:
    """The controller number the cell gives frame `name` (None: none given, or not a cell frame)."""
    if name is None:
        return None
    return next((f.number for f in cell.frames if f.name == name), None)


class NumberedData:
    """Numbers of one kind (tools or frames) in one program: given ones kept, the others
    numbered from `first` up in order of first use, skipping every number the cell gives
    to any item of that kind (so an automatic number never lands on a taught one)."""

    def __init__(self, given: set[int], first: int) -> None:
        self.given = given
        self.first = first
        self.numbers: dict[str | None, tuple[int, bool]] = {}  # name -> (number, was given)
        self.poses: dict[str | None, ir.Pose] = {}

    def number(self, name: str | None, given: int | None, pose: ir.Pose) -> int:
        if name not in self.numbers:
            if given is None:
                used = self.given | {n for n, _ in self.numbers.values()}
                n = self.first
                while n in used:
                    n += 1
                self.numbers[name] = (n, False)
            else:
                self.numbers[name] = (given, True)
            self.poses[name] = pose
        return self.numbers[name][0]
