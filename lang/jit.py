"""Kernels that run as plain Python on small inputs and compiled by numba on large ones.

numba costs ~0.6 s per process before its first compiled call returns (importing it, then
loading its registries and the cached machine code), which is most of what a small `rmot
check` or `rmot robots ik` waits for. A `Kernel` wraps ONE function body: `kernel.py` is the
function as written, run by the interpreter; `kernel.jit()` is the same function compiled by
`numba.njit(cache=True)` on first use (numba is imported only then). Callers pick by the size
of the work (`kernel(work, *args)`: compiled once the work done by the kernel in this process
reaches its threshold), so a small job never imports numba while a large one, or a loop of many
small calls, gets compiled speed. Both forms are one algorithm, the same bytecode: with only
+ - * / sqrt min max (the TOPP kernels) they give the same floats, bit for bit; where a kernel
calls math.sin/cos/atan2/acos, numba's versions and the interpreter's may differ in the last
bit (measured: 6 of 14,400 closed-form values, 1 ulp), which the tests bound.

`lists=True`: the interpreted form gets its array arguments as (nested) lists, for a body
that only reads them row by row (`row = a[i]; row[j]`: a view in numba, a list in Python).
A kernel calls its helpers by their plain module-level names; the compiled form gets a copy
of the module's globals in which each helper named in `uses` is replaced by its compiled form.
"""

from __future__ import annotations

import types
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

__all__ = ["Kernel"]


class Kernel:
    """One numba-compilable function, callable uncompiled (see the module docstring)."""

    def __init__(self, fn: Callable[..., Any], uses: Sequence[Kernel] = (), threshold: int = 0,
                 lists: bool = False) -> None:
        self.py = fn
        self.uses = tuple(uses)
        self.threshold = threshold
        self.lists = lists
        self._jit: Any = None
        self._work = 0  # done in the interpreter so far

    @property
    def compiled(self) -> bool:
        """Whether this process already has the compiled form (then it is the cheaper one)."""
        return self._jit is not None

    def prefer_compiled(self, work: int) -> bool:
        """Count `work` done through this kernel (by whatever form) and tell whether the compiled
        form should run it: already compiled, or the work so far reached the threshold."""
        self._work += work
        return self._jit is not None or self._work >= self.threshold

    def jit(self) -> Any:
        """The numba dispatcher of the same function (compiled, or loaded from numba's cache)."""
        if self._jit is None:
            import numba  # late: numba is heavy or optional, loaded only where used

            fn = self.py
            scope = dict(fn.__globals__)
            for helper in self.uses:
                scope[helper.py.__name__] = helper.jit()
            copy = types.FunctionType(fn.__code__, scope, fn.__name__, fn.__defaults__,
                                      fn.__closure__)
            copy.__qualname__, copy.__module__ = fn.__qualname__, fn.__module__
            copy.__doc__ = fn.__doc__
            self._jit = numba.njit(cache=True)(copy)
        return self._jit

    def __call__(self, work: int, *args: Any) -> Any:
        """Run on `args`: compiled when `work` (the caller's measure of the input's size, e.g.
        grid points x rows), added to the work this kernel did in the interpreter so far,
        reaches its threshold (then always), else as plain Python."""
        if self.prefer_compiled(work):
            return self.jit()(*args)
        if self.lists:  # read-only array arguments as (nested) lists: 3x faster to index
            args = tuple(a.tolist() if isinstance(a, np.ndarray) else a for a in args)
        return self.py(*args)
