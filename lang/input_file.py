"""Reading a file that a user, a program or a cache names: only a regular file is read, and
the open never blocks. A FIFO in a program's place (`mkfifo p.rmot`), a character device
(`/dev/zero`) or a folder is refused at once instead of blocking forever or being read until
memory runs out, and a file is never read past its bound.
"""

from __future__ import annotations

import errno
import os
import stat

__all__ = ["MAX_STAMPED_BYTES", "NotRegularFile", "read_regular"]

# The most a cache reads of one input file to hash it (programs, URDFs, meshes): a file larger
# than any input rmot loads is not hashed, and then no cache entry stands for it.
MAX_STAMPED_BYTES = 1 << 30


class NotRegularFile(OSError):
    """The path names a FIFO, device, socket or folder, or a file larger than its bound."""


def read_regular(path: str | os.PathLike[str], max_bytes: int, *, owner_only: bool = False,
                 follow_links: bool = True) -> bytes:
    """The bytes of `path`, a regular file of at most `max_bytes` bytes (with `owner_only`, also
    owned by this user and unreadable by others). Raises OSError (FileNotFoundError,
    PermissionError, ...) as open() does, and NotRegularFile for anything that is not such a
    file; opened with O_NONBLOCK so that a FIFO without a writer cannot block the open."""
    flags = os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_CLOEXEC", 0)
    if not follow_links:
        flags |= getattr(os, "O_NOFOLLOW", 0)
    fd = os.open(path, flags)
    try:
        st = os.fstat(fd)
        if not stat.S_ISREG(st.st_mode):
            raise NotRegularFile(errno.EINVAL, "not a regular file (a FIFO, device or folder)", os.fspath(path))
        if st.st_size > max_bytes:
            raise NotRegularFile(errno.EFBIG, f"larger than {max_bytes} bytes", os.fspath(path))
        if owner_only and (st.st_mode & 0o077 or (hasattr(os, "geteuid") and st.st_uid != os.geteuid())):
            raise NotRegularFile(errno.EACCES, "readable by others or owned by another user", os.fspath(path))
        chunks, left = [], max_bytes + 1
        while left > 0:
            chunk = os.read(fd, min(left, 1 << 20))
            if not chunk:
                break
            chunks.append(chunk)
            left -= len(chunk)
        data = b"".join(chunks)
        if len(data) > max_bytes:  # grew while being read
            raise NotRegularFile(errno.EFBIG, f"larger than {max_bytes} bytes", os.fspath(path))
        return data
    finally:
        os.close(fd)
