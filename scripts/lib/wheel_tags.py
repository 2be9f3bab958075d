"""The repaired wheel's tags, checked by scripts/lib/setup.sh (frictionsim_build_wheel) after `auditwheel repair`.

    python wheel_tags.py WHEEL        (auditwheel on PATH)

  - the file name's tags and the WHEEL file's Tag lines are the same set;
  - the interpreter and ABI tags are this interpreter's (cpXY-cpXY: the extension is built for one CPython);
  - every platform tag is a manylinux tag of this machine's architecture (no bare linux_*), its glibc no newer
    than this machine's, and `auditwheel show` finds the wheel consistent with the first of them (the most
    specific one, which auditwheel writes first);
  - nothing was grafted into the wheel (no frictionsim.libs/): every shared library the extension needs is on the
    manylinux policy's list (SUNDIALS is linked statically, KLU left out).
Prints auditwheel's reasons (the symbol versions that set the tag).
"""

from __future__ import annotations

import platform
import re
import subprocess
import sys
import zipfile
from pathlib import Path


def main(wheel: Path) -> int:
    problems = []
    name, version, python_tag, abi_tag, platform_tags = wheel.name[:-len(".whl")].split("-")
    named = {(p, a, t) for p in python_tag.split(".") for a in abi_tag.split(".") for t in platform_tags.split(".")}
    with zipfile.ZipFile(wheel) as archive:
        metadata = archive.read(f"{name}-{version}.dist-info/WHEEL").decode()
        grafted = [n for n in archive.namelist() if n.startswith(f"{name}.libs/")]
    declared = {tuple(line.split(":", 1)[1].strip().split("-")) for line in metadata.splitlines()
                if line.startswith("Tag:")}
    if declared != named:
        problems.append(f"the WHEEL file's tags {sorted(declared)} are not the file name's {sorted(named)}")

    here = f"cp{sys.version_info.major}{sys.version_info.minor}"
    if (python_tag, abi_tag) != (here, here):
        problems.append(f"interpreter/ABI tags {python_tag}-{abi_tag}, expected {here}-{here}")

    machine = platform.machine()
    glibc = tuple(int(x) for x in platform.libc_ver()[1].split("."))
    for tag in platform_tags.split("."):
        legacy = {"manylinux1": (2, 5), "manylinux2010": (2, 12), "manylinux2014": (2, 17)}
        match = re.fullmatch(r"manylinux_(\d+)_(\d+)_(\w+)", tag)
        arch_match = re.fullmatch(r"(manylinux1|manylinux2010|manylinux2014)_(\w+)", tag)
        if match:
            needs, arch = (int(match.group(1)), int(match.group(2))), match.group(3)
        elif arch_match:
            needs, arch = legacy[arch_match.group(1)], arch_match.group(2)
        else:
            problems.append(f"platform tag {tag} is not a manylinux tag")
            continue
        if arch != machine:
            problems.append(f"platform tag {tag} is not for this machine ({machine})")
        if needs > glibc:
            problems.append(f"platform tag {tag} needs glibc {needs}, this machine has {glibc}")

    shown = subprocess.run(["auditwheel", "show", str(wheel)], capture_output=True, text=True, check=True).stdout
    print(shown.strip(), file=sys.stderr)
    consistent = re.search(r'consistent\s+with\s+the\s+following\s+platform\s+tag:\s*"([^"]+)"', shown)
    first = platform_tags.split(".")[0]
    if not consistent or consistent.group(1) != first:
        problems.append(f"auditwheel show does not find the wheel consistent with {first}")
    if grafted:
        problems.append(f"auditwheel grafted shared libraries into the wheel: {grafted}")

    if problems:
        print(f"error: {wheel.name}:\n  " + "\n  ".join(problems), file=sys.stderr)
        return 1
    print(f"{wheel.name}: tags {python_tag}-{abi_tag}-{platform_tags}, consistent with auditwheel show "
          f"(glibc here {'.'.join(map(str, glibc))}), nothing grafted", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main(Path(sys.argv[1])))
