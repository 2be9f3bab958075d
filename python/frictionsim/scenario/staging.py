"""Outputs that appear all at once and replace nothing unasked: a command's (or a scenario run's) files are written
into a temporary directory beside the target and moved into it only when every one was written, and only where no
file of that name is there yet unless ``overwrite`` is given (the CLI's ``--force``). A blocked destination (an
existing output, a directory or a symbolic link in the way) leaves the target exactly as it was."""

from __future__ import annotations

import os
import shutil
import tempfile
from contextlib import contextmanager
from pathlib import Path
from typing import Iterator, List, Sequence

__all__ = ["OutputExistsError", "staged_directory"]


class OutputExistsError(FileExistsError):
    """Outputs would replace existing files; ``paths`` lists them (nothing was written). ``remedy`` says how to
    allow it (``overwrite=True`` in Python, ``--force`` on the command line)."""

    def __init__(self, paths: Sequence[Path], remedy: str = "pass overwrite=True to replace them") -> None:
        self.paths = [Path(p) for p in paths]
        self.remedy = remedy
        more = f" (and {len(self.paths) - 1} more of the outputs)" if len(self.paths) > 1 else ""
        super().__init__(f"{self.paths[0]} exists{more}; not overwritten: {remedy}")

    def __reduce__(self):
        return (type(self), (self.paths, self.remedy))


@contextmanager
def staged_directory(target, *, overwrite: bool = False) -> Iterator[Path]:
    """Yield a new temporary directory next to ``target``; when the block succeeds, move its contents into
    ``target`` (renamed into place if ``target`` does not exist yet), else delete it. Nothing half-written
    appears in ``target``. A file of ``target`` that the block also wrote is replaced only with ``overwrite``:
    else :class:`OutputExistsError` names it, and nothing is moved."""
    target = Path(target).absolute()
    target.parent.mkdir(parents=True, exist_ok=True)
    stage = Path(tempfile.mkdtemp(prefix=f".{target.name}.", suffix=".partial", dir=target.parent))
    try:
        yield stage
        mask = os.umask(0)
        os.umask(mask)
        os.chmod(stage, 0o777 & ~mask)  # mkdtemp makes it private; give it the usual permissions
        _commit(stage, target, overwrite)
    finally:
        shutil.rmtree(stage, ignore_errors=True)


def _commit(stage: Path, target: Path, overwrite: bool) -> None:
    if not target.exists():
        try:
            os.rename(stage, target)
            return
        except OSError:
            pass  # created meanwhile: merge below
    files = [source for source in sorted(stage.rglob("*")) if not source.is_dir()]
    # Check every destination before replacing any, so that a blocked one leaves the target as it was.
    existing: List[Path] = []
    for source in files:
        destination = target / source.relative_to(stage)
        if destination.is_dir() or any(p.exists() and not p.is_dir() for p in destination.parents
                                       if target in p.parents or p == target):
            raise OSError(f"cannot write {destination}: a directory or file is in the way")
        # a symbolic link below the target would carry the write elsewhere: never followed
        if destination.is_symlink() or any(p.is_symlink() for p in destination.parents if target in p.parents):
            raise OSError(f"cannot write {destination}: a symbolic link is in the way (not followed)")
        if os.path.lexists(destination):
            existing.append(destination)
    if existing and not overwrite:
        raise OutputExistsError(existing)
    for source in files:
        destination = target / source.relative_to(stage)
        destination.parent.mkdir(parents=True, exist_ok=True)
        if overwrite:
            os.replace(source, destination)
        else:  # linked in only where the name is still free (a file created meanwhile is not replaced either)
            try:
                os.link(source, destination)
            except FileExistsError:
                raise OutputExistsError([destination]) from None
            source.unlink()
