"""Sphinx extension: show the docstrings' plain-text mathematics as written.

frictionsim's docstrings (the Python modules' and the pybind11 bindings') are numpydoc, but their formulas are
plain text: absolute values ``|v_r|``, powers ``|b|^alpha``, ``**conditions`` in a call, and equations set off as
an indented block after a sentence. reStructuredText reads ``|x|`` as a substitution, ``**`` as bold and an
indented block as a quotation whose inline markup it parses, so before numpydoc sees a docstring this extension

* turns an indented block that follows a paragraph (not already introduced by ``::``) into a literal block: the
  equations keep their alignment and their characters;
* escapes, in prose outside inline literals and roles, every ``|`` and a ``*``/``**`` that opens no emphasis;
* names the bindings' "Keywords" section (the rig's keyword arguments, from its parameter table) "Other
  Parameters", numpydoc's section for them, and shows any other section numpydoc does not know (numpydoc would
  drop it), e.g. SoftString's "Conditions", under "Notes" with its title.

Doctest blocks (``>>>``) and existing literal blocks are left alone.
"""

from __future__ import annotations

import re
from typing import List

# ``literal`` and :role:`target` spans pass through untouched.
_PROTECTED = re.compile(r"(``.+?``|:[\w:.+-]+:`[^`]*`)")
# A '*' or '**' before a name that is not itself closed (``*word*`` is emphasis and stays).
_OPENING_STAR = re.compile(r"(?<![\w\\*])(\*\*?)(?=[A-Za-z_(\[])(?![^\s*]*\*)")


def _escape_prose(line: str) -> str:
    parts = _PROTECTED.split(line)
    for i in range(0, len(parts), 2):  # even parts are outside the protected spans
        text = parts[i].replace("\\|", "|").replace("|", "\\|")
        parts[i] = _OPENING_STAR.sub(lambda m: "\\" + "\\".join(m.group(1)), text)
    return "".join(parts)


def _indent(line: str) -> int:
    return len(line) - len(line.lstrip())


_NUMPYDOC_SECTIONS = {"Parameters", "Returns", "Yields", "Receives", "Raises", "Warns", "Other Parameters",
                      "Attributes", "Methods", "See Also", "Notes", "Warnings", "References", "Examples"}


def _numpydoc_sections(lines: List[str]) -> List[str]:
    out = list(lines)
    headers = [i for i in range(len(out) - 1)
               if out[i].strip() and set(out[i + 1].strip()) == {"-"} and len(out[i + 1].strip()) >= 3]
    has_notes = any(out[i].strip() == "Notes" for i in headers)
    for i in headers:
        title, indent = out[i].strip(), out[i][:_indent(out[i])]
        if title == "Keywords":
            out[i], out[i + 1] = indent + "Other Parameters", indent + "-" * len("Other Parameters")
        elif title not in _NUMPYDOC_SECTIONS and not has_notes:
            out[i], out[i + 1] = indent + "Notes", indent + "-----\n" + indent + f"**{title}**\n"
            has_notes = True
    return [part for line in out for part in line.split("\n")]


def plain_text_safe(lines: List[str]) -> List[str]:
    """The docstring's lines, with formula blocks made literal and stray inline markup escaped."""
    lines = _numpydoc_sections(lines)
    out: List[str] = []
    literal_below = None  # lines indented deeper than this belong to a literal block
    doctest = False
    prev_text, prev_indent, prev_blank = None, 0, True
    for line in lines:
        stripped = line.strip()
        indent = _indent(line)
        if literal_below is not None:
            if not stripped or indent > literal_below:
                out.append(line)
                prev_blank = not stripped
                continue
            literal_below = None
        if not stripped:
            doctest = False
            out.append(line)
            prev_blank = True
            continue
        if prev_blank and stripped.startswith(">>>"):
            doctest = True
        if doctest:
            out.append(line)
        elif prev_blank and prev_text is not None and indent > prev_indent:
            if not prev_text.endswith("::"):
                out += [" " * prev_indent + "::", ""]  # a paragraph of only '::' vanishes; the block is literal
            literal_below = prev_indent
            out.append(line)
        else:
            out.append(_escape_prose(line))
        prev_text, prev_indent, prev_blank = stripped, indent, False
    return out


def _process(app, what, name, obj, options, lines: List[str]) -> None:
    lines[:] = plain_text_safe(lines)


def setup(app):
    # before numpydoc (priority 500): numpydoc then parses the sections of the escaped text
    app.connect("autodoc-process-docstring", _process, priority=400)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
