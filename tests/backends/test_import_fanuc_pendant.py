"""Fanuc TP programs as a pendant saves them: the motion option `ACCn` on a linear move (the
acceleration override of the motion, J, L and C alike) read as the move's joint acceleration
share with W540 at its line; an override outside 1..100 keeps the move native.

Witness: the program follows a pendant-saved one by another author (WILDER-SYSTEMS-LLC's
git-ftp backup, job_dbl_safe_1.ls); the R-30iB Operator's Manual, motion option "Acceleration
override" (ACC 0..150, the motion's acceleration and deceleration time scaled); the expected
values are the file's numbers.
"""

from __future__ import annotations

from pathlib import Path

from click.testing import CliRunner

from rmot.backends.readers import read_files
from rmot.backends.readers.counts import motion_io_counts
from rmot.backends.readers.model import Cond, Conds, If, Move, Native, Pulse, SetOut, WaitIn, walk
from rmot.compiler.cli import cli

TP = """/PROG  JOB_DBL_SAFE_1
/ATTR
OWNER\t\t= MNEDITOR;
COMMENT\t\t= "";
DEFAULT_GROUP\t= 1,*,*,*,*;
/MN
   1:  UFRAME_NUM=4 ;
   2:  UTOOL_NUM=2 ;
   3:J P[1] 20% FINE ACC10    ;
   4:L P[2] 200mm/sec FINE ACC10    ;
   5:L P[1] 200mm/sec CNT50 ACC100    ;
   6:L P[2] 200mm/sec FINE ACC120    ;
/POS
P[1]{
   GP1:
\tUF : 4, UT : 2,\t\tCONFIG : 'F U T, 0, 0, 0',
\tX =      .044  mm,\tY =    -4.101  mm,\tZ =   300.000  mm,
\tW =     -.242 deg,\tP =     0.000 deg,\tR =     0.000 deg
};
P[2]{
   GP1:
\tUF : 4, UT : 2,\t\tCONFIG : 'F U T, 0, 0, 0',
\tX =  -249.056  mm,\tY =    -4.101  mm,\tZ =   300.000  mm,
\tW =     -.242 deg,\tP =     0.000 deg,\tR =     0.000 deg
};
/END
"""


def test_acc_on_linear_moves(tmp_path: Path) -> None:
    path = tmp_path / "job_dbl_safe_1.ls"
    path.write_text(TP)
    doc = read_files([str(path)])
    stmts = [s for r in doc.routines for s in walk(r.body)]
    moves = [s for s in stmts if isinstance(s, Move)]
    assert [(m.kind, m.speed, m.joint_pct, m.joint_accel, m.zone) for m in moves] == [
        ("joint", None, 20.0, 10.0, None),
        ("linear", 200.0, None, 10.0, None),
        ("linear", 200.0, None, None, 50.0),  # ACC100: the controller's own
    ]
    assert [s.text for s in stmts if isinstance(s, Native)] == ["L P[2] 200mm/sec FINE ACC120 ;"]
    w540 = [(d.span.start.line, d.span.start.col) for d in doc.diagnostics if d.code.id == "W540"]
    assert w540 == [(10, 4)]  # the line number of the TP line


def _read(tmp_path: Path, lines: list[str]) -> list[object]:
    body = "\n".join(f"{n:4d}:  {t} ;" for n, t in enumerate(lines, 1))
    path = tmp_path / "waits.ls"
    path.write_text(f"/PROG  WAITS\n/ATTR\n/MN\n{body}\n/POS\n/END\n")
    doc = read_files([str(path)])
    return [s for r in doc.routines for s in walk(r.body)]


def test_wait_on_several_inputs(tmp_path: Path) -> None:
    """Each parenthesised level joins its terms with one operator: read as and/or/not; a level
    mixing AND and OR, or a timer, stays native; a flag the program never sets is the input named
    after it (W549) (lines from the VASC backups)."""
    stmts = _read(tmp_path, [
        "WAIT (!DI[33] AND !DI[34] AND !DI[35] AND !DI[36])",
        "WAIT (!DI[129] OR DI[26])",
        "WAIT ((DI[718] AND !DI[772]) OR DI[26] OR DI[27])",
        "WAIT DI[1]=ON AND DI[2]=OFF",
        "WAIT (DI[1] AND DI[2] OR DI[3])",
        "WAIT (!F[329] OR DI[26])",
        "WAIT (DI[757] OR (TIMER[10]>=0))",
    ])
    waits = [s for s in stmts if isinstance(s, WaitIn)]
    assert [w.cond for w in waits] == [
        Conds("and", (Cond(33, False), Cond(34, False), Cond(35, False), Cond(36, False))),
        Conds("or", (Cond(129, False), Cond(26, True))),
        Conds("or", (Conds("and", (Cond(718, True), Cond(772, False))), Cond(26, True), Cond(27, True))),
        Conds("and", (Cond(1, True), Cond(2, False))),
        Conds("or", (Cond("F[329]", False), Cond(26, True))),
    ]
    assert [s.text for s in stmts if isinstance(s, Native)] == [
        "WAIT (DI[1] AND DI[2] OR DI[3]) ;", "WAIT (DI[757] OR (TIMER[10]>=0)) ;"]


def test_german_pendant_words(tmp_path: Path) -> None:
    """A German controller's `A[n]=AN|AUS` is DO[n]=ON|OFF and `WARTE (E[n])` WAIT (DI[n]) (the
    export is read in English words: fanuc_german)."""
    stmts = _read(tmp_path, ["A[15:PF0 Robot (Punto Cero)]=AN", "A[17:Rob.En Mantenimiento]=(AUS)",
                             "WARTE (E[9])", "WARTE (!E[9] AND E[10])"])
    assert [(s.signal, s.value) for s in stmts if isinstance(s, SetOut)] == [(15, 1.0), (17, 0.0)]
    assert [s.cond for s in stmts if isinstance(s, WaitIn)] == [
        Cond(9, True), Conds("and", (Cond(9, False), Cond(10, True)))]


def test_a_background_edit_copy_is_read_as_the_program_it_is(tmp_path: Path) -> None:
    """kamilkozdro/FanucProgramAnalyze keeps the pendant's `/PROG  -BCKED8-` (OWNER = BACKGRND, no
    instructions): a file that starts with `/PROG` is read, never refused as not being TP."""
    path = tmp_path / "-bcked8-.ls"
    path.write_text("/PROG  -BCKED8-\n/ATTR\nOWNER\t\t= BACKGRND;\nCOMMENT\t\t= \"\";\n/MN\n/POS\n/END\n")
    doc = read_files([str(path)])
    assert doc.name == "-BCKED8-" and [len(r.body) for r in doc.routines] == [0]


def test_an_if_with_an_output_action(tmp_path: Path) -> None:
    """`IF (cond),DO[n]=..` (B-83284EN, IF with an action) is `if cond { set/pulse }`; an action
    rmot has no form for (a group output, a robot output) keeps the line native, and the import
    summary counts it as the I/O instruction its action is."""
    stmts = _read(tmp_path, ["IF (DI[5]),DO[3]=PULSE,3.0sec", "IF (!DI[2] AND DI[9]),DO[7]=(OFF)",
                             "IF (DI[1]),GO[1]=31", "IF (DI[1] OR DO[4]),DO[8]=ON", "IF (DI[1]),RO[2]=ON"])
    ifs = [s for s in stmts if isinstance(s, If)]
    assert [(i.cond, i.then) for i in ifs] == [
        (Cond(5, True), (Pulse(3, 3.0, ifs[0].where),)),
        (Conds("and", (Cond(2, False), Cond(9, True))), (SetOut(7, 0.0, ifs[1].where),)),
        (Conds("or", (Cond(1, True), Cond(4, True, True))), (SetOut(8, 1.0, ifs[2].where),))]
    assert [s.text for s in stmts if isinstance(s, Native)] == ["IF (DI[1]),GO[1]=31 ;", "IF (DI[1]),RO[2]=ON ;"]
    doc = read_files([str(tmp_path / "waits.ls")])
    assert list(motion_io_counts(doc).values()) == [(3, 1)]  # the RO line is I/O kept native; GO is no rmot I/O word


def test_a_damaged_position_value_is_refused_and_an_untaught_one_is_no_target(tmp_path: Path) -> None:
    """`X = .4.965` (a damaged file) is E510 at its position, not read as 0.4 mm; `X = ********`
    is how the pendant writes a position never taught (VASC MOTN011.LS): no target."""
    damaged = tmp_path / "damaged.ls"
    damaged.write_text(TP.replace("X =      .044  mm", "X =      .4.965  mm"))
    result = CliRunner().invoke(cli, ["import", str(damaged), "-o", str(tmp_path / "d.rmot")], catch_exceptions=False)
    assert result.exit_code == 2 and "damaged.ls:14:1: error[E510]: P[1]'s `X = .4.965` must be a number" in result.output
    untaught = tmp_path / "untaught.ls"
    untaught.write_text(TP.replace("X =      .044  mm", "X =   ********  mm"))
    doc = read_files([str(untaught)])
    assert [t.name for t in doc.targets] == ["job_dbl_safe_1_p2"]
