"""The hardening outcome table shared by every property-test module (issues 11 and 23): each generated input is
counted under its input class as one of OUTCOME_COLUMNS; the suite prints the table at its end (conftest.py's
terminal summary) and, with FRICTIONSIM_HARDENING_TABLE=path, appends it to that file (the closing note's table).
"""

from __future__ import annotations

import collections
import os

#: what a generated input can end in ("tried" is their sum)
OUTCOME_COLUMNS = ("clean rejection", "finite result", "crash", "hang", "NaN as success", "wrong kind of error",
                   "silent nonsense", "data loss")

#: input class -> outcome -> count
OUTCOMES: dict = collections.defaultdict(collections.Counter)


def record(input_class: str, what: str) -> None:
    """Count one input of `input_class` as `what` (one of OUTCOME_COLUMNS)."""
    if what not in OUTCOME_COLUMNS:
        raise ValueError(f"outcome {what!r} is not one of {OUTCOME_COLUMNS}")
    OUTCOMES[input_class][what] += 1


def table() -> str:
    """The markdown table of the outcomes counted so far ('' when none)."""
    if not OUTCOMES:
        return ""
    lines = ["| input class | tried | " + " | ".join(OUTCOME_COLUMNS) + " |", "|" + "---|" * (len(OUTCOME_COLUMNS) + 2)]
    totals: collections.Counter = collections.Counter()
    for name, counts in sorted(OUTCOMES.items()):
        totals.update(counts)
        lines.append(f"| {name} | {sum(counts.values())} | " + " | ".join(str(counts[c]) for c in OUTCOME_COLUMNS)
                     + " |")
    lines.append(f"| **total** | {sum(totals.values())} | " + " | ".join(str(totals[c]) for c in OUTCOME_COLUMNS)
                 + " |")
    return "\n".join(lines)


def write_table() -> None:
    """Append the table to FRICTIONSIM_HARDENING_TABLE when it names a file."""
    path = os.environ.get("FRICTIONSIM_HARDENING_TABLE")
    text = table()
    if path and text:
        with open(path, "a") as out:
            out.write(text + "\n")
