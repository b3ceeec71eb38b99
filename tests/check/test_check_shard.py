"""`rmot check --shard K/N` and `rmot merge-reports`: a CI matrix checks every program exactly
once, and the merged report equals an unsharded run of the same programs (sorted by path)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from click.testing import CliRunner
from hypothesis import given, settings
from hypothesis import strategies as st

from rmot.compiler.cli import cli
from rmot.compiler.cli.shard import Shard, assign, parse_shard, select_shard

# Three small programs of different sizes on the built-in default cell (fast to plan).
PROGRAMS = {
    "a.rmot": "program a on r1 {\n  move joint joints(0, -10, 10, 0, 90, 0) deg\n}\n",
    "b.rmot": ("program b on r1 {\n  move joint joints(0, -10, 10, 0, 90, 0) deg\n"
               "  move joint joints(20, -10, 10, 0, 90, 0) deg\n  wait 0.5 s\n}\n"),
    "c.rmot": ("program c on r1 {\n  move joint joints(0, -10, 10, 0, 90, 0) deg\n"
               "  move linear pose(x=5000mm, z=500mm)   # out of reach: E220\n}\n"),
    "d.rmot": "program d on r1 {\n  wait 0.1 s\n}\n",
}


class TestParseShard:
    @pytest.mark.parametrize(("text", "expected"), [("1/1", Shard(1, 1)), ("2/4", Shard(2, 4)), (" 3 / 3 ", Shard(3, 3))])
    def test_accepts_k_of_n(self, text: str, expected: Shard) -> None:
        """K/N with 1 <= K <= N parses."""
        assert parse_shard(text) == expected

    @pytest.mark.parametrize("text", ["0/3", "4/3", "1/0", "a/b", "1", "-1/3", "1/3/4", "1.5/3", "1/99999"])
    def test_refuses_the_rest(self, text: str) -> None:
        """Anything else is a ValueError whose message says what is expected."""
        with pytest.raises(ValueError, match="must be"):
            parse_shard(text)


names = st.text(alphabet="abcdefgh/_.", min_size=1, max_size=8)


@settings(max_examples=200, deadline=None)
@given(st.dictionaries(names, st.integers(0, 10_000), min_size=0, max_size=40), st.integers(1, 12), st.randoms())
def test_shards_partition_and_balance(sizes: dict[str, int], count: int, rnd) -> None:
    """Every program lands in exactly one shard; the assignment ignores the order the programs
    were given in; and the largest shard obeys Graham's list-scheduling bound
    (max load <= total / N + largest program), computed here from the sizes alone."""
    programs = list(sizes)
    shards = assign(programs, count, sizes)
    assert len(shards) == count
    flat = [p for s in shards for p in s]
    assert sorted(flat) == sorted(programs)
    shuffled = programs[:]
    rnd.shuffle(shuffled)
    assert [sorted(s) for s in assign(shuffled, count, sizes)] == [sorted(s) for s in shards]
    if programs:
        loads = [sum(sizes[p] for p in s) for s in shards]
        assert max(loads) <= sum(sizes.values()) / count + max(sizes.values())
    for k, s in enumerate(shards, start=1):  # within a shard: the order given
        assert s == [p for p in programs if p in set(s)]
        assert select_shard(programs, Shard(k, count), sizes) == s


def _write(tmp_path: Path) -> list[str]:
    for name, text in PROGRAMS.items():
        (tmp_path / name).write_text(text, encoding="utf-8")
    return sorted(PROGRAMS)


@pytest.mark.parametrize("fmt", ["junit", "sarif", "json"])
def test_merged_shards_equal_the_unsharded_run(fmt: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """Shards 1..3 of 3, merged in reverse order, give the same bytes as one run over all."""
    monkeypatch.chdir(tmp_path)
    programs = _write(tmp_path)
    runner = CliRunner()
    whole = runner.invoke(cli, ["check", *programs, "--format", fmt, "-o", "whole"])
    assert whole.exit_code == 1, whole.output  # c.rmot has an unreachable target
    parts = []
    exits = []
    for k in (1, 2, 3):
        result = runner.invoke(cli, ["check", *reversed(programs), "--shard", f"{k}/3", "--format", fmt, "-o", f"s{k}"])
        exits.append(result.exit_code)
        parts.append(f"s{k}")
    assert sorted(exits) == [0, 0, 1]  # exactly one shard holds the failing program
    merged = runner.invoke(cli, ["merge-reports", *reversed(parts), "-o", "merged"])
    assert merged.exit_code == 0, merged.output
    assert (tmp_path / "merged").read_text(encoding="utf-8") == (tmp_path / "whole").read_text(encoding="utf-8")


def test_more_shards_than_programs_is_an_empty_clean_shard(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """Shard 4/4 of three programs checks nothing and succeeds with an empty report."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "a.rmot").write_text(PROGRAMS["a.rmot"], encoding="utf-8")
    result = CliRunner().invoke(cli, ["check", "a.rmot", "--shard", "2/2", "--format", "json"])
    assert result.exit_code == 0, result.output
    assert json.loads(result.output)["programs"] == []


@pytest.mark.parametrize("text", ["0/2", "3/2", "x"])
def test_bad_shard_is_a_usage_error(text: str, tmp_path: Path) -> None:
    """A malformed --shard is exit 2 naming the option."""
    (tmp_path / "a.rmot").write_text(PROGRAMS["a.rmot"], encoding="utf-8")
    result = CliRunner().invoke(cli, ["check", str(tmp_path / "a.rmot"), "--shard", text])
    assert result.exit_code == 2
    assert "--shard" in result.output


JUNIT = '<?xml version="1.0"?>\n<testsuites><testsuite><testcase name="p.rmot" /></testsuite></testsuites>\n'


@pytest.mark.parametrize(("files", "code"), [
    ({"a.xml": '<?xml version="1.0"?>\n<!DOCTYPE x [<!ENTITY e "boom">]>\n<testsuites>&e;</testsuites>\n'}, "E531"),
    ({"a.json": '{"version": 1, "programs": [{"file": "p", "cycle_time_s": NaN, "diagnostics": []}]}'}, "E531"),
    ({"a.txt": "p.rmot: ok: cycle time 1.000 s\n"}, "E531"),
    ({"a.xml": "<report/>"}, "E531"),
    ({"a.xml": JUNIT, "b.json": '{"version": 1, "programs": []}'}, "E532"),
    ({"a.json": '{"version": 1, "programs": []}', "b.json": '{"version": 2, "programs": []}'}, "E532"),
])
def test_merge_refuses_what_it_cannot_merge(files: dict[str, str], code: str, tmp_path: Path) -> None:
    """Entity declarations, NaN, text reports, other XML, mixed formats and versions: exit 2 with the code."""
    paths = []
    for name, text in files.items():
        (tmp_path / name).write_text(text, encoding="utf-8")
        paths.append(str(tmp_path / name))
    result = CliRunner().invoke(cli, ["merge-reports", *paths])
    assert result.exit_code == 2, result.output
    assert f"error[{code}]" in result.output
    assert "Traceback" not in result.output


def test_merge_io_errors_are_diagnostics(tmp_path: Path) -> None:
    """A missing input is E530 and an -o in a missing directory is E533, both exit 2."""
    result = CliRunner().invoke(cli, ["merge-reports", str(tmp_path / "absent.xml")])
    assert result.exit_code == 2 and "error[E530]" in result.output
    (tmp_path / "a.xml").write_text(JUNIT, encoding="utf-8")
    result = CliRunner().invoke(cli, ["merge-reports", str(tmp_path / "a.xml"), "-o", str(tmp_path / "no" / "m.xml")])
    assert result.exit_code == 2 and "error[E533]" in result.output
