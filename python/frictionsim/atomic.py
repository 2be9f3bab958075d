"""Files written whole or not at all: every writer of the package (CSV, netCDF, parquet, PNG, metadata.json) writes
to a temporary name in the target's folder and renames it into place (:func:`os.replace`, atomic on POSIX and
Windows within one file system), so a process killed mid-write leaves the earlier file intact under the final name,
never a truncated one, and its temporary file is removed when the write fails. The ground floor of the package:
this module imports nothing of it.

    >>> with atomic_path("run.nc") as temporary:
    ...     dataset.to_netcdf(temporary)          # run.nc appears only once this block has succeeded
"""

from __future__ import annotations

import os
import tempfile
from contextlib import contextmanager
from pathlib import Path
from typing import Iterator, Union

__all__ = ["atomic_path", "write_bytes", "write_csv", "write_text"]


@contextmanager
def atomic_path(path: Union[str, Path], *, replace: bool = True) -> Iterator[Path]:
    """Yield a new temporary file beside ``path`` to write; when the block succeeds, rename it onto ``path``
    (replacing a file there, never writing through a symbolic link of that name), else delete it. With
    ``replace=False`` it is linked in only where nothing (no file, no link) has that name: FileExistsError else.

    The temporary name keeps ``path``'s suffix (``.run.k3j2x9.nc``), for writers that pick the format by it
    (matplotlib's savefig, pandas' compression); it starts with a dot, so listings of finished outputs skip it.
    Ctrl-C, SIGTERM raised as an exception or an error in the block remove it; only SIGKILL can leave it behind,
    and then beside the intact earlier file.

    Returns
    -------
    pathlib.Path
        ``path`` once renamed (the caller returns it).
    """
    path = Path(path)
    descriptor, name = tempfile.mkstemp(prefix=f".{path.stem}.", suffix=path.suffix or ".tmp", dir=path.parent)
    os.close(descriptor)
    temporary = Path(name)
    try:
        yield temporary
        os.chmod(temporary, 0o666 & ~_umask())  # mkstemp's file is private; give it what open() would
        if replace:
            os.replace(temporary, path)
        else:
            os.link(temporary, path)  # atomic, and refuses an existing name (a symbolic link counts)
            temporary.unlink()
    except BaseException:
        temporary.unlink(missing_ok=True)
        raise


def write_text(path: Union[str, Path], text: str, encoding: str = "utf-8") -> Path:
    """``Path(path).write_text(text)``, whole or not at all (see :func:`atomic_path`); returns ``path``."""
    with atomic_path(path) as temporary:
        temporary.write_text(text, encoding=encoding)
    return Path(path)


def write_bytes(path: Union[str, Path], data: bytes) -> Path:
    """``Path(path).write_bytes(data)``, whole or not at all (see :func:`atomic_path`); returns ``path``."""
    with atomic_path(path) as temporary:
        temporary.write_bytes(data)
    return Path(path)


def write_csv(frame, path: Union[str, Path], *, index: bool = False, float_format: str = "%.10g") -> Path:
    """``frame.to_csv(path, index=index, float_format=float_format)`` (a pandas DataFrame; ten significant digits,
    the package's tables), whole or not at all (see :func:`atomic_path`); returns ``path``."""
    with atomic_path(path) as temporary:
        frame.to_csv(temporary, index=index, float_format=float_format)
    return Path(path)


def _umask() -> int:
    """The process's umask, read without changing it where the system says it (Linux 4.7+): setting and restoring
    it, the portable way, would briefly give files another thread creates meanwhile the permissions 0666."""
    try:
        with open("/proc/self/status", encoding="ascii") as status:
            for line in status:
                if line.startswith("Umask:"):
                    return int(line.split()[1], 8)
    except (OSError, ValueError, IndexError):
        pass
    mask = os.umask(0o022)
    os.umask(mask)
    return mask
