"""Run every reproducer of tests/robust/cases.py in its own subprocess under a time and memory
cap, and print which still fail and how (traceback, hang, memory, crash, wrong result).

    .venv/bin/python -m tests.robust.survey [NAME_SUBSTRING]
"""

from __future__ import annotations

import json
import resource
import subprocess
import sys
import tempfile

from tests.robust.cases import CASES


def _child(name: str, d: str) -> None:
    resource.setrlimit(resource.RLIMIT_AS, (2 << 30, 2 << 30))
    from tests.robust.runner import run_case

    case = next(c for c in CASES if c.name == name)
    out = run_case(case, d)
    print(json.dumps({"exit": out.exit_code, "exc": repr(out.exception) if out.exception else None,
                      "output": out.output[-3000:], "files": {k: v.decode("utf-8", "replace") for k, v in out.files.items()}}))


def main() -> None:
    pick = sys.argv[1] if len(sys.argv) > 1 else ""
    for case in CASES:
        if pick not in case.name:
            continue
        with tempfile.TemporaryDirectory() as d:
            try:
                p = subprocess.run([sys.executable, "-m", "tests.robust.survey", "--child", case.name, d],
                                   capture_output=True, text=True, timeout=60)
            except subprocess.TimeoutExpired:
                print(f"HANG      {case.name}")
                continue
            if p.returncode != 0:
                kind = "MEMORY" if "MemoryError" in p.stderr else f"CRASH{p.returncode}"
                print(f"{kind:9} {case.name} {p.stderr[-300:]!r}")
                continue
            r = json.loads(p.stdout.strip().splitlines()[-1])
            problems = []
            if r["exc"]:
                problems.append(f"traceback {r['exc']}")
            if r["exit"] not in case.exit_codes:
                problems.append(f"exit {r['exit']}")
            problems += [f"missing {c!r}" for c in case.codes if c not in r["output"]]
            problems += [f"injected {a!r}" for a in case.absent if any(a in t for t in r["files"].values())]
            print(f"{'ok' if not problems else 'FAIL':9} {case.name} {'; '.join(problems)}")
            if problems and "-v" in sys.argv:
                print("    " + r["output"][-800:].replace("\n", "\n    "))


if __name__ == "__main__":
    if len(sys.argv) > 1 and sys.argv[1] == "--child":
        _child(sys.argv[2], sys.argv[3])
    else:
        main()
