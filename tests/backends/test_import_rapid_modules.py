"""RAPID modules of one task as controller backups hold them (RAPID/TASK1/PROGMOD/*.mod): a
module's moves use the tools, speeds and targets another module declares (global data are the
task's: RAPID Overview, "Scope of data"), LOCAL data stay in their module, data declared below
the PROC that uses it are read, an inline robtarget carries its pose and its cfx branch, and a
move kept native says which data the files given do not declare.

Witnesses: the module texts follow zwj12's ZhongXunRapid backup (CalibDataModule declares
`toolWeldGun`, WeldTestModule moves with it); the expected pose is computed here with scipy's
Rotation from the literal's quaternion (scalar first in RAPID), not by the reader.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
from scipy.spatial.transform import Rotation

from rmot.backends.readers import read_files
from rmot.backends.readers.model import Move, Native, walk

CALIB = """MODULE CalibDataModule
    TASK PERS tooldata toolWeldGun:=[TRUE,[[-60.4407,4.01094,538.005],[0.981627,0,0.190809,0]],[3,[0,0,1],[1,0,0,0],0,0,0]];
    LOCAL PERS speeddata speedLocal:=[50,500,5000,1000];
    PERS speeddata speedAir:=[300,500,5000,1000];
ENDMODULE
"""

WELD = """MODULE WeldTestModule
    PROC main()
        MoveJ pWGReady,speedAir,z10,toolWeldGun;
        MoveL [[-301.19,34.29,849.89],[0.119305,-0.0528558,0.924955,-0.356975],[-1,-1,1,1],
            [9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]],v100,fine,toolWeldGun;
        MoveL pWGReady,speedLocal,fine,toolWeldGun;
    ENDPROC
    TASK PERS robtarget pWGReady:=[[2571.80,-1031.86,873.30],[0.361306,-0.103756,-0.907486,0.187513],[-1,0,-1,0],
        [9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]];
ENDMODULE
"""


def _read(tmp_path: Path, *modules: tuple[str, str]) -> tuple[list[Move], list[Native], list[str]]:
    paths = []
    for name, text in modules:
        (tmp_path / name).write_text(text)
        paths.append(str(tmp_path / name))
    doc = read_files(paths)
    stmts = [s for r in doc.routines for s in walk(r.body)]
    w510 = [d.message for d in doc.diagnostics if d.code.id == "W510"]
    return [s for s in stmts if isinstance(s, Move)], [s for s in stmts if isinstance(s, Native)], w510


def test_task_modules_share_global_data(tmp_path: Path) -> None:
    moves, natives, w510 = _read(tmp_path, ("WeldTestModule.mod", WELD), ("CalibDataModule.mod", CALIB))
    assert [(m.kind, m.target_name, m.speed, m.joint_pct, m.zone, m.tool) for m in moves] == [
        ("joint", "pWGReady", None, 100.0, 10.0, "toolWeldGun"),  # declared below main, speed from the other module
        ("linear", None, 100.0, None, None, "toolWeldGun"),
    ]
    # speedLocal is LOCAL to CalibDataModule: the third move names data its module cannot see
    assert [n.text for n in natives] == ["MoveL pWGReady,speedLocal,fine,toolWeldGun;"]
    assert len(w510) == 1 and w510[0].startswith("speedLocal is not declared in the files given")


def test_inline_robtarget_pose_and_a_lone_module(tmp_path: Path) -> None:
    moves, natives, w510 = _read(tmp_path, ("WeldTestModule.mod", WELD))
    assert moves == [] and len(natives) == 3
    assert w510[0].startswith("speedAir, toolWeldGun are not declared in the files given")
    moves, _, _ = _read(tmp_path, ("WeldTestModule.mod", WELD), ("CalibDataModule.mod", CALIB))
    inline = moves[1]
    assert inline.pose is not None
    w, x, y, z = 0.119305, -0.0528558, 0.924955, -0.356975
    expected = Rotation.from_quat([x, y, z, w]).as_quat()  # normalised by scipy
    got = np.array(inline.pose.quaternion)
    assert np.allclose(inline.pose.position, [-0.30119, 0.03429, 0.84989], atol=1e-12)
    assert min(np.abs(got - np.r_[expected[3], expected[:3]]).max(), np.abs(got + np.r_[expected[3], expected[:3]]).max()) < 1e-9
