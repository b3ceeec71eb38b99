"""Legal vendor names: legalisation, deterministic clash resolution, warnings."""

from __future__ import annotations

import pytest

from rmot.backends import codes
from rmot.backends.names import DataPool, NameRules, NameTable, legalize

KRLISH = NameRules(max_len=8, upper=True, reserved=frozenset({"END"}))


class TestLegalize:
    @pytest.mark.parametrize(("name", "expected"), [
        ("pick", "PICK"), ("pick-place", "PICK_PLA"), ("2nd", "R2ND"), ("end", "END_"),
        ("héllo", "H_LLO"), ("", "R"),
    ])
    def test_rules(self, name: str, expected: str) -> None:
        """Illegal characters become '_', a bad first character gets a prefix, length is cut."""
        assert legalize(name, KRLISH) == expected


class TestNameTable:
    def test_clash_renamed_with_warning(self) -> None:
        """Two names equal after legalisation: the second gets _2 and a W401 warning."""
        table = NameTable(KRLISH, "krl")
        assert table.name("approach_a") == "APPROACH"
        assert table.name("approach_b") == "APPROA_2"
        clash = [d for d in table.diagnostics if d.code is codes.NAME_CLASH]
        assert len(clash) == 1 and "approach_b" in clash[0].message and "APPROA_2" in clash[0].message

    def test_same_source_same_name(self) -> None:
        """Asking for a name twice gives the same legal name and no new warning."""
        table = NameTable(KRLISH, "krl")
        first = table.name("pick")
        assert table.name("pick") == first and table.diagnostics == []

    def test_case_only_change_is_silent(self) -> None:
        """Upper-casing for a case-insensitive vendor is not a rename."""
        table = NameTable(KRLISH, "krl")
        table.name("home")
        assert table.diagnostics == []

    def test_changed_name_warns(self) -> None:
        """A legalised name that differs beyond case is reported (W400)."""
        table = NameTable(KRLISH, "krl")
        table.name("pick-it")
        assert [d.code for d in table.diagnostics] == [codes.NAME_CHANGED]

    def test_reserved_by_backend(self) -> None:
        """A name the backend reserved (e.g. main) is never handed out."""
        table = NameTable(NameRules(max_len=32), "rapid")
        table.reserve("main")
        assert table.name("main") == "main_2"

    def test_deterministic(self) -> None:
        """The same requests in the same order give the same names."""
        names = ["a-b", "a_b", "a.b", "ab"]
        runs = []
        for _ in range(2):
            table = NameTable(KRLISH, "krl")
            runs.append([table.name(n) for n in names])
        assert runs[0] == runs[1] == ["A_B", "A_B_2", "A_B_3", "AB"]


class TestDataPool:
    def test_identical_values_share_a_name(self) -> None:
        """Same hint and value -> one declaration; a different value -> hint_2."""
        pool = DataPool(NameTable(NameRules(max_len=32), "rapid"))
        assert pool.add("p", "robtarget:[1]") == "p"
        assert pool.add("p", "robtarget:[1]") == "p"
        assert pool.add("p", "robtarget:[2]") == "p_2"
        assert pool.items == [("p", "robtarget:[1]"), ("p_2", "robtarget:[2]")]

    def test_data_names_avoid_routine_names(self) -> None:
        """Data and routines share one namespace."""
        table = NameTable(NameRules(max_len=32), "rapid")
        table.name("pick")
        assert DataPool(table).add("pick", "robtarget:[1]") == "pick_2"
