"""The source distribution's file list, checked by scripts/lib/setup.sh (frictionsim_build_wheel) before the wheel
is built from it.

    python sdist_check.py SDIST [SOURCE_TREE]

It must hold what a build needs: the top-level files that pyproject.toml and CMakeLists.txt read, and, where
SOURCE_TREE is a git checkout, every tracked file of the folders the extension's build reads (cmake/, include/,
bindings/, python/) that exists in the tree. It must hold nothing of a build: no build directory (build/,
build-*/), no out/, no virtual environment, no compiled object, extension or wheel, no bytecode.
Prints the size and the number of files per top-level entry.
"""

from __future__ import annotations

import collections
import subprocess
import sys
import tarfile
from pathlib import Path, PurePosixPath

#: What `pip wheel SDIST` reads besides the build folders below.
TOP_LEVEL = ("pyproject.toml", "CMakeLists.txt", "LICENSE", "README.md", "PKG-INFO")
#: The folders the extension's CMake build and the wheel's packaging read, file by file.
BUILD_FOLDERS = ("cmake", "include", "bindings", "python")
#: Directory names that only a build, a run or an environment leaves (.gitignore's).
BUILD_DIRS = {"build", "out", ".venv", "__pycache__", "dist", ".git"}
BUILD_SUFFIXES = (".so", ".o", ".a", ".pyc", ".whl", ".egg-info")


def main(sdist: Path, tree: Path | None) -> int:
    with tarfile.open(sdist) as archive:
        members = [m for m in archive.getmembers() if m.isfile()]
    roots = {PurePosixPath(m.name).parts[0] for m in members}
    if len(roots) != 1:
        print(f"error: {sdist.name} has {len(roots)} top-level folders: {sorted(roots)}", file=sys.stderr)
        return 1
    files = {str(PurePosixPath(*PurePosixPath(m.name).parts[1:])) for m in members}
    problems = []

    for name in TOP_LEVEL:
        if name not in files:
            problems.append(f"missing {name}")
    if tree is not None and (tree / ".git").exists():
        tracked = subprocess.run(["git", "-C", str(tree), "ls-files", "-z", "--", *BUILD_FOLDERS],
                                 capture_output=True, check=True).stdout.decode().split("\0")
        # a tracked file deleted in the working tree is not there to pack
        needed = {name for name in tracked if name and (tree / name).is_file()}
        problems += [f"missing {name} (tracked, read by the build)" for name in sorted(needed - files)]
    elif not any(name.startswith("bindings/") for name in files):
        problems.append("no bindings/ sources")

    for name in sorted(files):
        parts = PurePosixPath(name).parts
        if any(part in BUILD_DIRS or part.startswith("build-") for part in parts[:-1]) or \
                name.endswith(BUILD_SUFFIXES) or any(part.endswith(".egg-info") for part in parts):
            problems.append(f"a build's file: {name}")

    per_root = collections.Counter(PurePosixPath(name).parts[0] if "/" in name else "." for name in files)
    size = sdist.stat().st_size
    unpacked = sum(m.size for m in members)
    print(f"{sdist.name}: {size / 1e6:.2f} MB ({unpacked / 1e6:.2f} MB unpacked), {len(files)} files: "
          + ", ".join(f"{root} {count}" for root, count in sorted(per_root.items())), file=sys.stderr)
    if problems:
        print(f"error: {sdist.name}:\n  " + "\n  ".join(problems), file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(Path(sys.argv[1]), Path(sys.argv[2]) if len(sys.argv) > 2 else None))
