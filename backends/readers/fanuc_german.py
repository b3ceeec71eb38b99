"""A German-language Fanuc pendant's TP export read in the English keywords the reader knows.

A controller set to German writes the same program in German words: `WARTE (!E[706] [+]
(TIMER[10]>=0))` for `WAIT (!DI[706] OR (TIMER[10]>=0))`, `A[129]=(AN)` for `DO[129]=(ON)`. The
table is every substitution seen between the German and the English exports of the same 101
programs of one controller's backup (JuniorNatalin/VASC, BVTU KJBVTU211160R01, GERMAN and ENGLISH
folders; listed in tests/data/vendor_programs/fanuc/MEASURED): translated, each instruction and
position line of the German export is the English export's line. No other word is translated:
comments (`! ..` lines, `[n:comment]`), a message's text and the program a call names stay as
written. Lines keep their places, so every diagnostic points at the German line.
"""

from __future__ import annotations

import re

__all__ = ["is_german", "english"]

# whole instruction words and phrases, German -> English, as the two exports write them
_WORDS = (
    ("SPRUNG LABEL[", "JMP LBL["), ("LABEL[", "LBL["), ("ZEIT VOR", "TB"), ("WEG VOR", "DB"),
    ("IRQ BEDINGUNG", "SKIP CONDITION"), ("FREIG. PREG", "UNLOCK PREG"), ("SPERRE PR", "LOCK PREG"),
    ("WARTE", "WAIT"), ("WENN", "IF"), ("AUFRUF", "CALL"), ("SONST", "ELSE"), ("IST", "SELECT"),
    ("ENDE", "END"), ("STOPP", "STOP"), ("MELDUNG[", "MESSAGE["), ("BALM[", "UALM["),
    ("FB-PSPS", "TC_ONLINE"), ("WKZ_NUM", "UTOOL_NUM"),
    ("BENUTZER_NUM", "UFRAME_NUM"), ("TRAGLST[", "PAYLOAD["), ("Interrupt,", "Skip,"),
    ("WKZ_Offset ,", "Tool_Offset,"),
    ("max_Geschw.", "max_speed"), ("KONFIG", "CONFIG"),
    ("gA[", "GO["), ("gE[", "GI["), ("A[", "DO["), ("E[", "DI["), ("i[", "R["),
    ("[&]", "AND"), ("[+]", "OR"), ("AN", "ON"), ("AUS", "OFF"),
)
_WORD = re.compile("|".join(
    (r"(?<![\w\]])(?<!\w/)" if german[0].isalnum() else "") + re.escape(german) + (r"(?![\w.])" if german[-1].isalnum() else "")
    for german, _ in _WORDS))
_ENGLISH = {german: english for german, english in _WORDS}
# kept as written: a comment line, a bracket's comment, a message's text, a quoted name, the
# program a call names
_KEPT = re.compile(r"^\s*\d*:?\s*!.*$|(?<=\[)\d+:[^\]]*(?=\])|(?<=MELDUNG\[)[^\]]*|'[^']*'|\"[^\"]*\""
                   r"|(?<=AUFRUF )\w+")
_SPEED = re.compile(r"(?<=\d)(mm/)?sek\b")  # `.10sek`, `10mm/sek`
_MARKS = re.compile(r"(?m)^\s*\d+:\s*(?:WARTE|WENN|AUFRUF|SPRUNG|LABEL\[|A\[\d+[^\]]*\]\s*=)|^(?:EIGN\.|KOMMENTAR|ERSTELL)\s")


def is_german(text: str) -> bool:
    """Whether a TP export is in German: its header's German keys (`EIGN.`, `KOMMENTAR`,
    `ERSTELL`) or an instruction that starts with a German word."""
    return _MARKS.search(text) is not None


def english(text: str) -> str:
    """The export in the English words (see the module docstring), line for line; `text`
    itself when it is not German."""
    if not is_german(text):
        return text
    return "\n".join(_line(line) for line in text.split("\n"))


def _line(line: str) -> str:
    out, at = [], 0
    for kept in _KEPT.finditer(line):
        out.append(_words(line[at:kept.start()]))
        out.append(kept.group(0))
        at = kept.end()
    out.append(_words(line[at:]))
    return "".join(out)


def _words(part: str) -> str:
    return _SPEED.sub(lambda m: f"{m.group(1) or ''}sec", _WORD.sub(lambda m: _ENGLISH[m.group(0)], part))
