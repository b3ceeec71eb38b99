"""`rmot lsp`: latency from a didChange to the front end's diagnostics, for a 500-line program,
measured over stdio from a separate client process, against the floor of a bare parse of the
same text (and of the whole front end) in this process, in the same run.

    python tests/benchmarks/bench_lsp.py [ROUNDS] [--plan]   # medians (ms)
    pytest tests/benchmarks/bench_lsp.py                     # the same, as a pytest run

Each round changes one move's target to a typo or back (whole-document sync, a new version
each time) and waits for the publishDiagnostics of that version; the typo rounds must carry
E101, the others none (so the timing is of a real answer). By default the server runs with
`--no-plan` (planning would start 0.3 s after the change in another process, competing for
the same cores); `--plan` measures with it on. Target: a median within 100 ms.
"""

from __future__ import annotations

import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

LINES = 500


def program(lines: int = LINES) -> str:
    """A single-task program of `lines` lines: targets on a grid and a move to each."""
    out = ["program big on r1 {", "  tool gripper", "  speed 250 mm/s", "  zone 10 mm", ""]
    k = 0
    while len(out) < lines - 1:
        x, y = 300 + 20 * (k % 10), -100 + 20 * (k // 10 % 10)
        out.append(f"  target t{k} = pose(x={x}mm, y={y}mm, z=500mm, rx=180deg)   # grid point {k}")
        out.append(f"  move linear t{k}")
        k += 1
    out.append("}")
    return "\n".join(out) + "\n"


class StdioClient:
    """The least LSP client: Content-Length framed JSON-RPC over a child's pipes."""

    def __init__(self, command: list[str]) -> None:
        self.process = subprocess.Popen(command, stdin=subprocess.PIPE, stdout=subprocess.PIPE)
        self.next_id = 0

    def send(self, method: str, params: Any, request: bool = False) -> int | None:
        message: dict[str, Any] = {"jsonrpc": "2.0", "method": method, "params": params}
        if request:
            self.next_id += 1
            message["id"] = self.next_id
        body = json.dumps(message).encode()
        assert self.process.stdin is not None
        self.process.stdin.write(b"Content-Length: %d\r\n\r\n" % len(body) + body)
        self.process.stdin.flush()
        return message.get("id")

    def receive(self) -> dict[str, Any]:
        assert self.process.stdout is not None
        length = 0
        while (line := self.process.stdout.readline().strip()):
            if line.lower().startswith(b"content-length:"):
                length = int(line.split(b":")[1])
        return json.loads(self.process.stdout.read(length))  # type: ignore[no-any-return]

    def wait(self, accept: Any) -> dict[str, Any]:
        while True:
            message = self.receive()
            if accept(message):
                return message

    def close(self) -> None:
        request = self.send("shutdown", None, request=True)
        self.wait(lambda m: m.get("id") == request)
        self.send("exit", None)
        self.process.wait(timeout=10)


def _seconds(fn: Any) -> float:
    t0 = time.perf_counter()
    fn()
    return time.perf_counter() - t0


def measure(rounds: int = 40, plan: bool = False) -> dict[str, float]:
    from rmot.compiler.cli import tune_gc
    from rmot.compiler.lsp.analysis import analyze
    from rmot.lang.parse import parse_text

    tune_gc()  # the collector's schedule of an `rmot` process, the server's too (compiler/cli)

    rmot = shutil.which("rmot", path=os.path.dirname(sys.executable)) or "rmot"
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "big.rmot"
        text = program()
        path.write_text(text, encoding="utf-8")
        uri = path.as_uri()
        client = StdioClient([rmot, "lsp", *([] if plan else ["--no-plan"])])
        init = client.send("initialize", {"processId": None, "rootUri": None, "capabilities": {}}, request=True)
        client.wait(lambda m: m.get("id") == init)
        client.send("initialized", {})
        client.send("textDocument/didOpen", {"textDocument": {"uri": uri, "languageId": "rmot", "version": 1, "text": text}})
        client.wait(lambda m: m.get("method") == "textDocument/publishDiagnostics")
        latencies, parses, fronts = [], [], []
        for version in range(2, rounds + 2):  # the floors interleaved with the rounds: same load
            parses.append(_seconds(lambda: parse_text(text, str(path))))
            fronts.append(_seconds(lambda: analyze(str(path), text)))
            typo = version % 2 == 0
            changed = text.replace("move linear t7\n", "move linear t7x\n") if typo else text
            t0 = time.perf_counter()
            client.send("textDocument/didChange", {"textDocument": {"uri": uri, "version": version},
                                                   "contentChanges": [{"text": changed}]})
            got = client.wait(lambda m, v=version: m.get("method") == "textDocument/publishDiagnostics"
                              and m["params"].get("version") == v)
            latencies.append(time.perf_counter() - t0)
            codes = [d["code"] for d in got["params"]["diagnostics"]]
            assert codes == (["E101"] if typo else []), codes
        client.close()
        return {"lines": float(text.count("\n")),
                "didChange -> diagnostics (median ms)": 1000 * statistics.median(latencies),
                "didChange -> diagnostics (p90 ms)": 1000 * statistics.quantiles(latencies, n=10)[-1],
                "bare parse, in process (median ms)": 1000 * statistics.median(parses),
                "whole front end, in process (median ms)": 1000 * statistics.median(fronts),
                "didChange -> diagnostics / bare parse": statistics.median(latencies) / statistics.median(parses)}


def test_bench_lsp() -> None:
    for name, value in measure(rounds=20).items():
        print(f"{name:42s} {value:8.1f}")


if __name__ == "__main__":
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    results = measure(int(args[0]) if args else 40, plan="--plan" in sys.argv)
    for name, value in results.items():
        print(f"{name:42s} {value:8.1f}")
