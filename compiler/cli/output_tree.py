"""`rmot compile`'s writer: each vendor directory replaced whole and atomically.

For each vendor, every file is written into a fresh staging directory beside the final one
(`OUTDIR/.rmot-stage-<vendor>-<pid>-<n>`), flushed to disk, and the staging directory then
takes the vendor directory's place in one step:
  * Linux: renameat2(RENAME_EXCHANGE) swaps the two directories atomically; the old one,
    now under the staging name, is removed afterwards;
  * elsewhere, or when the file system refuses the exchange: the old directory is renamed
    aside (`.rmot-old-...`) and the new one into place; a run killed between the two renames
    leaves no vendor directory and the old one aside, which the next run restores first.
So at every instant, also after SIGKILL, `OUTDIR/<vendor>` is entirely the old output or
entirely the new one, never a mix; a vendor that is not written keeps its old directory; a
killed run leaves only hidden `.rmot-*` directories, removed by the next run.
"""

from __future__ import annotations

import ctypes
import itertools
import os
import shutil

from rmot.lang.atomic import write_new, write_text

__all__ = ["MARKER", "ForeignOutputDir", "write_vendor_dirs"]

_SEQ = itertools.count()
_RENAME_EXCHANGE = 2  # linux/fs.h
# OUTDIR/.rmot.output lists, one a line, the vendor directories rmot wrote there: a non-empty
# directory not listed is the user's (or another tool's) and is never replaced. The list sits
# beside the vendor directories, not in them, so a vendor directory copied to a controller
# holds only the controller's files.
MARKER = ".rmot.output"


class ForeignOutputDir(OSError):
    """OUTDIR/<vendor> exists, is not empty and was not written by rmot."""


def _renameat2() -> object | None:
    try:
        # the C library this process already has loaded (dlopen(NULL)), not a search:
        # ctypes.util.find_library runs ldconfig in a subprocess, ~7 ms of every compile
        fn = ctypes.CDLL(None, use_errno=True).renameat2
    except (OSError, AttributeError):
        return None
    fn.argtypes = [ctypes.c_int, ctypes.c_char_p, ctypes.c_int, ctypes.c_char_p, ctypes.c_uint]
    fn.restype = ctypes.c_int
    return fn


_AT_FDCWD = -100


def exchange(a: str, b: str) -> bool:
    """Atomically swap the directories a and b; False when the system cannot."""
    fn = _renameat2()
    if fn is None:
        return False
    if fn(_AT_FDCWD, os.fsencode(a), _AT_FDCWD, os.fsencode(b), _RENAME_EXCHANGE) == 0:  # type: ignore[operator]
        return True
    err = ctypes.get_errno()
    if err in (22, 38, 95):  # EINVAL, ENOSYS, EOPNOTSUPP: no exchange on this system / file system
        return False
    raise OSError(err, os.strerror(err), b)


def _fsync_dir(path: str) -> None:
    try:
        fd = os.open(path, os.O_RDONLY)
    except OSError:
        return
    try:
        os.fsync(fd)
    except OSError:
        pass
    finally:
        os.close(fd)


def recover(outdir: str) -> None:
    """Undo what a killed run left: restore a vendor directory left aside, drop staging ones."""
    try:
        names = os.listdir(outdir)
    except OSError:
        return
    for name in sorted(names):
        path = os.path.join(outdir, name)
        if name.startswith(".rmot-old-"):
            vendor = name[len(".rmot-old-"):].rsplit("-", 2)[0]
            final = os.path.join(outdir, vendor)
            if not os.path.exists(final):
                os.rename(path, final)
                continue
            shutil.rmtree(path, ignore_errors=True)
        elif name.startswith(".rmot-stage-"):
            pid = name.rsplit("-", 2)[-2]
            if not (pid.isdigit() and int(pid) != os.getpid() and _alive(int(pid))):
                shutil.rmtree(path, ignore_errors=True)


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True


def write_vendor_dirs(outdir: str, vendors: dict[str, dict[str, str]]) -> list[str]:
    """Write vendor -> {relative name: text} as OUTDIR/<vendor>/<name>; returns the final
    paths in order. Each vendor directory is replaced whole (see the module doc); an OSError
    leaves every vendor not yet swapped as it was, and no staging directory behind."""
    os.makedirs(outdir, exist_ok=True)
    recover(outdir)
    own = _own_vendors(outdir)
    for vendor in vendors:
        _require_own(os.path.join(outdir, vendor), own)
    if not set(vendors) <= own:
        write_text(os.path.join(outdir, MARKER), "".join(f"{v}\n" for v in sorted(own | set(vendors))))
    written: list[str] = []
    for vendor, files in vendors.items():
        final = os.path.join(outdir, vendor)
        stage = os.path.join(outdir, f".rmot-stage-{vendor}-{os.getpid()}-{next(_SEQ)}")
        try:
            os.mkdir(stage)
            for rel, text in files.items():
                path = os.path.join(stage, *rel.split("/"))
                os.makedirs(os.path.dirname(path), exist_ok=True)
                write_new(path, text)  # the one writer (lang/atomic.py): umask mode, fsync
            _fsync_dir(stage)
            _swap(stage, final, outdir, vendor)
        finally:
            if os.path.lexists(stage):
                shutil.rmtree(stage, ignore_errors=True)
        _fsync_dir(outdir)
        written += [os.path.join(final, *rel.split("/")) for rel in files]
    return written


def _swap(stage: str, final: str, outdir: str, vendor: str) -> None:
    if not os.path.lexists(final):
        os.replace(stage, final)
        return
    if not os.path.isdir(final) or os.path.islink(final):
        raise IsADirectoryError(21, f"output for {vendor} must go to a directory (got a file or link)", final)
    if exchange(stage, final):
        return  # the old tree now sits at `stage`; the caller removes it
    aside = os.path.join(outdir, f".rmot-old-{vendor}-{os.getpid()}-{next(_SEQ)}")
    os.rename(final, aside)
    os.rename(stage, final)
    shutil.rmtree(aside, ignore_errors=True)


def _own_vendors(outdir: str) -> set[str]:
    """The vendor directories OUTDIR's MARKER lists (none when it is missing or unreadable)."""
    try:
        with open(os.path.join(outdir, MARKER), encoding="utf-8") as f:
            return {line.strip() for line in f.read(1 << 16).splitlines() if line.strip()}
    except (OSError, UnicodeDecodeError):
        return set()


def _require_own(final: str, own: set[str]) -> None:
    """ForeignOutputDir when `final` is a non-empty directory MARKER does not list."""
    if not os.path.isdir(final) or os.path.islink(final) or os.path.basename(final) in own:
        return
    if os.listdir(final):
        raise ForeignOutputDir(17, f"folder not written by rmot (not listed in {MARKER})", final)
