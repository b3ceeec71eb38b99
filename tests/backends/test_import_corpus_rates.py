"""The share of motion and I/O instructions `rmot import` reads (not kept native) in real
programs by other people, per vendor.

The targets are ≥ 90 % for RAPID, KRL and URScript and ≥ 75 % for Fanuc TP and INFORM, over a
corpus of vendor programs laid out one folder per vendor (`rapid/`, `krl/`, `fanuc/`,
`urscript/`, `inform/`). The repository's own corpus (tests/data/vendor_programs, with each
file's source and licence) is mostly ROS driver programs, sockets and registers rather than
taught paths: there each vendor must stay at or above the share measured when the corpus was
gathered (a reader change that loses instructions fails). A larger corpus of programs whose
licences do not allow copying them here (their sources are listed in
tests/data/vendor_programs/README.md) is measured with `python -m tests.backends.test_import_corpus_rates DIR`, which exits 1
below a target.

Witness: which instructions are motion or I/O is decided from each native line's first word
against the vendors' instruction lists (readers/counts.py, citing the manuals), not by the
readers under test; the corpus files are other people's.
"""

from __future__ import annotations

from pathlib import Path


from rmot.backends.readers import ImportError_
from rmot.backends.readers.counts import motion_io_counts
from rmot.compiler.cli.import_read import read_on_robot

CORPUS = Path(__file__).resolve().parents[1] / "data" / "vendor_programs"
PROGRAMS = (".mod", ".prg", ".modx", ".src", ".ls", ".script", ".urscript", ".jbi")
TARGETS = {"rapid": 90.0, "krl": 90.0, "urscript": 90.0, "fanuc": 75.0, "inform": 75.0}
# the shares measured on the repository's corpus (imported, all), raised as the readers learn forms
# (URScript: a library function's `sleep` inside its polling loop stays native with the loop)
FLOORS = {"rapid": (47, 55), "krl": (24, 29), "urscript": (145, 158), "fanuc": (10, 30), "inform": (15, 24)}


def _shares(root: Path) -> dict[str, tuple[int, int]]:
    """vendor -> (motion and I/O instructions imported, all of them) over the vendor's files."""
    out: dict[str, tuple[int, int]] = {}
    for folder in sorted(p for p in root.iterdir() if p.is_dir()):
        imported = total = 0
        for path in sorted(p for p in folder.iterdir() if p.suffix.lower() in PROGRAMS):
            try:
                doc = read_on_robot([str(path)], None, None, None)  # as `rmot import FILE` reads it
            except ImportError_:
                continue  # a file that is not the language: a located E510 (test_import_corpus)
            for kept, native in motion_io_counts(doc).values():
                imported, total = imported + kept, total + kept + native
        out[folder.name] = (imported, total)
    return out


def test_repository_corpus_keeps_its_measured_share() -> None:
    shares = _shares(CORPUS)
    assert set(shares) == set(FLOORS)
    for vendor, (imported, total) in shares.items():
        floor_imported, floor_total = FLOORS[vendor]
        assert total == floor_total, (vendor, total)  # the same instructions are counted
        assert imported >= floor_imported, (vendor, imported, floor_imported)


def meets_the_targets(root: Path) -> list[str]:
    """The vendors of the corpus at `root` whose share is below its target, with their counts."""
    below = []
    for vendor, (imported, total) in _shares(root).items():
        if vendor in TARGETS and total and 100.0 * imported / total < TARGETS[vendor]:
            below.append(f"{vendor}: {imported}/{total} ({100.0 * imported / total:.1f} %)")
    return below


def test_the_target_check_names_a_vendor_below_its_target(tmp_path: Path) -> None:
    """A corpus whose only RAPID move is kept native is reported below the 90 % target."""
    (tmp_path / "rapid").mkdir()
    (tmp_path / "rapid" / "m.mod").write_text(
        "MODULE M\n  PROC main()\n    MoveAbsJ Unknown_Form_1, v100, fine, tool0;\n  ENDPROC\nENDMODULE\n",
        encoding="utf-8",
    )
    imported, total = _shares(tmp_path)["rapid"]
    assert total >= 1 and imported < total
    assert [line.split(":")[0] for line in meets_the_targets(tmp_path)] == ["rapid"]


if __name__ == "__main__":
    # A corpus outside the repository (licences that forbid copying): `python -m
    # tests.backends.test_import_corpus_rates DIR` prints the shares and exits 1 below a target.
    import sys

    root = Path(sys.argv[1])
    for vendor, (imported, total) in _shares(root).items():
        print(f"{vendor}: {imported}/{total} motion and I/O instructions imported")
    failed = meets_the_targets(root)
    print("below target: " + "; ".join(failed) if failed else "every vendor meets its target")
    sys.exit(1 if failed else 0)
