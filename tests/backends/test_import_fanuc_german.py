"""A German-language pendant's TP export is read as its English export.

Witness: the same controller's programs exported in both languages (JuniorNatalin/VASC, BVTU
backup KJBVTU211160R01, GERMAN and ENGLISH folders; fanuc/MEASURED). Each pair below is one
line of one program as the two exports write it, quoted from them; `english` must turn the
German into the English, and the reader must then read both alike. Measured over all 101 paired
programs: every instruction and position line translates to the English export's line (two of
them up to the pendant's column padding).
"""

from __future__ import annotations

from pathlib import Path

import pytest

from rmot.backends.readers import read_files
from rmot.backends.readers.fanuc_german import english, is_german
from rmot.backends.readers.model import walk

# (German export, English export) of one line, by vocabulary entry
PAIRS = [
    ("   4:  WENN gA[3]<=97,SPRUNG LABEL[1] ;", "   4:  IF GO[3]<=97,JMP LBL[1] ;"),
    ("   4:J P[1] 10% CNT0 ACC100 ZEIT VOR   0.00sek,P-SPS    ;", "   4:J P[1] 10% CNT0 ACC100 TB   0.00sec,P-SPS    ;"),
    ("   8:J PR[10] 100% CNT0 WEG VOR    0.0mm,P-SPS    ;", "   8:J PR[10] 100% CNT0 DB    0.0mm,P-SPS    ;"),
    ("   3:  IRQ BEDINGUNG E[718]=AN [+] $EQZ.$EQ_SOFTMODE=0    ;",
     "   3:  SKIP CONDITION DI[718]=ON OR $EQZ.$EQ_SOFTMODE=0    ;"),
    ("   1:  FREIG. PREG ;", "   1:  UNLOCK PREG ;"),
    ("  13:  SPERRE PR ;", "  13:  LOCK PREG ;"),
    ("  33:  WARTE E[877]=AN    ;", "  33:  WAIT DI[877]=ON    ;"),
    ("   2:  AUFRUF EQEXTTYP(1) ;", "   2:  CALL EQEXTTYP(1) ;"),
    ("  13:  ENDE ;", "  13:  END ;"),
    ("   4:  TIMER[1]=STOPP ;", "   4:  TIMER[1]=STOP ;"),
    ("  83:  MELDUNG[Int.: E1/2.Startup END] ;", "  83:  MESSAGE[Int.: E1/2.Startup END] ;"),
    ("  12:  BALM[1] ;", "  12:  UALM[1] ;"),
    ("   1:  FB-PSPS (AN) ;", "   1:  TC_ONLINE (ON) ;"),
    ("   1:  WKZ_NUM=1 ;", "   1:  UTOOL_NUM=1 ;"),
    ("   2:  BENUTZER_NUM=0 ;", "   2:  UFRAME_NUM=0 ;"),
    ("   3:  TRAGLST[1] ;", "   3:  PAYLOAD[1] ;"),
    ("  10:L P[1] 10mm/sek CNT0 ACC250 Interrupt,LABEL[1]    ;", "  10:L P[1] 10mm/sec CNT0 ACC250 Skip,LBL[1]    ;"),
    ("  14:J PR[51] 100% CNT100 ACC100 WKZ_Offset ,PR[52]    ;", "  14:J PR[51] 100% CNT100 ACC100 Tool_Offset,PR[52]    ;"),
    ("   8:L P[1] max_Geschw. CNT0 ACC100    ;", "   8:L P[1] max_speed CNT0 ACC100    ;"),
    ("\tUF : 0, UT : 1,\t\tKONFIG : 'F U T, 0, 1, 0',", "\tUF : 0, UT : 1,\t\tCONFIG : 'F U T, 0, 1, 0',"),
    ("  41:  F[742]=((gE[31]>=(gA[31]-140)) [&] (gE[31]<=(gA[31]+140))) ;",
     "  41:  F[742]=((GI[31]>=(GO[31]-140)) AND (GI[31]<=(GO[31]+140))) ;"),
    ("   3:  i[819]=$JCR.$JOG_GP ;", "   3:  R[819]=$JCR.$JOG_GP ;"),
    ("  19:  F[79]=((E[786] [&] !E[788]) [+] (!E[788] [&] E[130])) ;",
     "  19:  F[79]=((DI[786] AND !DI[788]) OR (!DI[788] AND DI[130])) ;"),
    ("  23:  A[22925]=AUS ;", "  23:  DO[22925]=OFF ;"),
    ("   7:  A[129]=(AN) ;", "   7:  DO[129]=(ON) ;"),
    ("  67:  A[718]=(!E[718]) ;", "  67:  DO[718]=(!DI[718]) ;"),
    ("  15:  //A[10105]=AUS ;", "  15:  //DO[10105]=OFF ;"),
    # a call's argument names and a comment stay as written
    ("   4:  AUFRUF VW_USER(Basic1,EZSP,Nr1,ProgNr=99, , ,S-Punkt=1838,Fzg_Typ=3,EIN/AUS=AN) ;",
     "   4:  CALL VW_USER(Basic1,EZSP,Nr1,ProgNr=99, , ,S-Punkt=1838,Fzg_Typ=3,EIN/AUS=ON) ;"),
    ("   6:  !Apagar Perfil AN E[1] ;", "   6:  !Apagar Perfil AN E[1] ;"),
    ("  30:  A[120:Averia AN]=(AUS) ;", "  30:  DO[120:Averia AN]=(OFF) ;"),
]

HEADER = "/PROG  FOLGE011\n/ATTR\nEIGN.\t\t= MNEDITOR;\nKOMMENTAR\t= \"\";\n/MN\n"


@pytest.mark.parametrize("german, expected", PAIRS)
def test_a_german_line_is_its_english_exports_line(german: str, expected: str) -> None:
    assert english(HEADER + german).split("\n")[-1] == expected


def test_the_program_a_call_names_is_not_translated() -> None:
    """A program may be named like a German word (`AN`): the name a call gives stays as written."""
    assert english(HEADER + "   5:  AUFRUF AN ;").split("\n")[-1] == "   5:  CALL AN ;"


def test_an_english_export_is_left_as_it_is() -> None:
    """No German header key and no German instruction: not one character changes, even a
    program named like a German word (`CALL AN`)."""
    text = "/PROG  MAIN\n/ATTR\nOWNER\t\t= MNEDITOR;\n/MN\n   1:  CALL AN ;\n   2:  DO[1]=ON ;\n/POS\n/END\n"
    assert not is_german(text) and english(text) == text


PROGRAM = """{header}   1:  {tool} ;
   2:  {frame} ;
   3:J P[1] 100% CNT0 ;
   4:  {out} ;
   5:  {wait} ;
   6:  {test},{jump} ;
   7:  {out2} ;
   8:  {label} ;
   9:L P[1] 100mm/{sec} FINE ;
/POS
P[1]{{
   GP1:
\tUF : 0, UT : 1,\t\t{config} : 'N U T, 0, 0, 0',
\tX =   500.000  mm,\tY =     0.000  mm,\tZ =   500.000  mm,
\tW =   180.000 deg,\tP =     0.000 deg,\tR =     0.000 deg
}};
/END
"""
GERMAN = dict(header="/PROG  DE\n/ATTR\nEIGN.\t\t= MNEDITOR;\n/MN\n", tool="WKZ_NUM=1", frame="BENUTZER_NUM=0",
              out="A[129]=(AN)", wait="WARTE (!E[706] [&] E[707])", test="WENN (E[5])", jump="SPRUNG LABEL[2]",
              out2="A[130]=AUS", label="LABEL[2]", sec="sek", config="KONFIG")
ENGLISH = dict(header="/PROG  DE\n/ATTR\nOWNER\t\t= MNEDITOR;\n/MN\n", tool="UTOOL_NUM=1", frame="UFRAME_NUM=0",
               out="DO[129]=(ON)", wait="WAIT (!DI[706] AND DI[707])", test="IF (DI[5])", jump="JMP LBL[2]",
               out2="DO[130]=OFF", label="LBL[2]", sec="sec", config="CONFIG")


def test_a_german_program_reads_as_its_english_export(tmp_path: Path) -> None:
    """Read through `rmot import`'s reading, the German file gives the statements the English
    one does (the moves, the outputs, the wait on two inputs, the if a jump builds), located at
    the German file's lines, and W551 says once that it was read in English words: the German
    jump skips the output it jumps over, as the English one does."""
    docs = []
    for name, words in (("de", GERMAN), ("en", ENGLISH)):
        path = tmp_path / name / "DE.ls"
        path.parent.mkdir()
        path.write_text(PROGRAM.format(**words))
        doc = read_files([str(path)])
        assert [d.span.start.line for d in doc.diagnostics if d.code.id == "W551"] == ([1] if name == "de" else [])
        docs.append(([type(s).__name__ for r in doc.routines for s in walk(r.body)],
                     [s for r in doc.routines for s in walk(r.body) if type(s).__name__ != "Native"]))
    (kinds_de, stmts_de), (kinds_en, stmts_en) = docs
    assert kinds_de == kinds_en == ["Move", "SetOut", "WaitIn", "If", "SetOut", "Move"]
    assert [str(s).replace("/de/", "/en/") for s in stmts_de] == [str(s) for s in stmts_en]


def test_each_import_reads_the_files_as_they_are_now(tmp_path: Path) -> None:
    """A file is read once per import and again by the next: an edit between two imports (a
    German export replaced by an English one with another output) is seen, and W551 follows it."""
    path = tmp_path / "DE.ls"
    path.write_text(PROGRAM.format(**GERMAN))
    first = read_files([str(path)])
    path.write_text(PROGRAM.format(**{**ENGLISH, "out": "DO[131]=(ON)"}))
    second = read_files([str(path)])
    assert [d.code.id for d in first.diagnostics].count("W551") == 1
    assert "W551" not in [d.code.id for d in second.diagnostics]
    outs = [[s.signal for r in d.routines for s in walk(r.body) if type(s).__name__ == "SetOut"] for d in (first, second)]
    assert outs == [[129, 130], [131, 130]]
