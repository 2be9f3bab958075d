"""The engine's friction laws by key, and the parameters of engine classes.

:func:`law_classes` is the one mapping from a law's key (a scenario's ``friction.type``: "coulomb", "stribeck",
"dahl", "lugre", "elasto_plastic") to its class in :mod:`frictionsim._core`; the scenario schema and everything
else that names laws by key read it from here. :func:`parameters` gives the keyword parameters of a law, rig or
function (name, default, required, value kind): from the class's ``parameters`` records where the engine exports
them, else from its signature (the pybind11 docstring signature, or the "Keywords" section of a class that takes
``**kwargs``, such as :class:`frictionsim.TorsionalRig`).
"""

from __future__ import annotations

import ast
import functools
import inspect
import re
from typing import Any, Dict, List, NamedTuple, Optional, Tuple

from ._core import FRICTION_LAWS

__all__ = ["Parameter", "UnknownLawError", "law_class", "law_classes", "parameters"]

def law_classes() -> Dict[str, type]:
    """Law key -> engine class, e.g. ``{"coulomb": frictionsim.Coulomb, ..., "elasto_plastic": ...}``: the
    engine's registry ``frictionsim._core.FRICTION_LAWS`` (each class's ``key``), in its order."""
    return {cls.key: cls for cls in FRICTION_LAWS}


class UnknownLawError(KeyError, ValueError):
    """No engine law has this key; the message lists the keys there are."""

    def __str__(self) -> str:
        return str(self.args[0]) if self.args else ""


def law_class(key: str) -> type:
    """The engine class of law ``key``; raises :class:`UnknownLawError` (a KeyError and a ValueError) naming the
    known keys."""
    classes = law_classes()
    if key not in classes:
        raise UnknownLawError(f"unknown friction law {key!r} (known: {', '.join(classes)})")
    return classes[key]


class Parameter(NamedTuple):
    """A keyword parameter: ``default`` is None where ``required``; ``kind`` is float, int, bool, str or tuple (a
    sequence of ``size`` numbers)."""

    name: str
    default: Any
    required: bool
    kind: type = float
    size: Optional[int] = None


@functools.lru_cache(maxsize=None)
def parameters(source: Any, skip: Tuple[str, ...] = ("self", "friction")) -> Tuple[Parameter, ...]:
    """The keyword parameters of ``source`` (an engine class, or a Python function), in signature order, without
    those named in ``skip``: every keyword of its signature, each described by the class's ``parameters`` record
    where the engine's table has one (the numbers), else as the signature gives it (switches, polynomials)."""
    records = getattr(source, "parameters", None)
    tabled = {}
    if isinstance(records, (list, tuple)):
        tabled = {r.name: Parameter(r.name, r.default, bool(r.required), _kind_of(r.default)) for r in records}
    # the signature lists every keyword; the table, where there is one, is what its numbers are
    signature = _from_signature(source)
    found = [tabled.get(p.name, p) for p in signature] if signature else list(tabled.values())
    return tuple(p for p in found if p.name not in skip)


def _from_signature(source: Any) -> List[Parameter]:
    source = inspect.unwrap(source)  # frictionsim.units wraps the engine's routines; the signature is the engine's
    if not inspect.isclass(source) and not _is_builtin(source):  # a Python function
        return [Parameter(p.name, None if p.default is p.empty else p.default, p.default is p.empty,
                          _kind_of(p.default, p.annotation))
                for p in inspect.signature(source).parameters.values()
                if p.kind in (p.POSITIONAL_OR_KEYWORD, p.KEYWORD_ONLY)]
    try:
        doc = (source.__init__.__doc__ if inspect.isclass(source) else source.__doc__) or ""
    except UnicodeDecodeError:  # a docstring the extension does not hold as UTF-8: no signature to read
        return []
    match = re.match(r"\s*\w+\((.*)\)\s*->", doc)
    if match is None:
        return []
    arguments = _split(match.group(1))
    if any(a.strip().startswith("**") for a in arguments):
        return _from_keywords_section(inspect.getdoc(source) or "")
    out = []
    for argument in arguments:
        name, _, rest = argument.partition(":")
        annotation, has_default, default = rest.partition("=")
        name = name.strip()
        if not name or name.startswith("*"):
            continue
        value = _literal(default.strip()) if has_default else None
        out.append(Parameter(name, value, not has_default, *_kind_of_annotation(annotation)))
    return out


def _from_keywords_section(doc: str) -> List[Parameter]:
    """``name : type = default`` lines of a numpydoc "Keywords" section."""
    section = re.search(r"^Keywords\n-+\n(.*?)(?:\n\S[^\n]*\n-+\n|\Z)", doc, re.S | re.M)
    out = []
    for line in (section.group(1).splitlines() if section else []):
        entry = re.match(r"(\w+) : ([\w.]+)(?: = (.+))?$", line)
        if entry:
            kind = {"bool": bool, "int": int, "str": str}.get(entry.group(2), float)
            out.append(Parameter(entry.group(1), _literal(entry.group(3)) if entry.group(3) else None,
                                 entry.group(3) is None, kind))
    return out


def _split(arguments: str) -> List[str]:
    """Split a signature's argument list at the commas outside brackets."""
    parts, depth, start = [], 0, 0
    for i, char in enumerate(arguments):
        if char in "[(":
            depth += 1
        elif char in "])":
            depth -= 1
        elif char == "," and depth == 0:
            parts.append(arguments[start:i])
            start = i + 1
    parts.append(arguments[start:])
    return [p for p in parts if p.strip()]


def _kind_of_annotation(annotation: str) -> Tuple[type, Optional[int]]:
    size = re.search(r"FixedSize\((\d+)\)", annotation)
    if size or "Sequence" in annotation:
        return tuple, int(size.group(1)) if size else None
    words = set(re.findall(r"[\w]+", annotation))
    for word, kind in (("bool", bool), ("str", str), ("SupportsFloat", float), ("float", float), ("int", int)):
        if word in words:
            return kind, None
    return float, None


def _kind_of(default: Any, annotation: Any = inspect.Parameter.empty) -> type:
    if isinstance(annotation, str):
        return _kind_of_annotation(annotation)[0]
    if isinstance(annotation, type) and annotation is not inspect.Parameter.empty:
        return annotation
    if isinstance(default, (bool, str, tuple)):
        return type(default)
    return tuple if isinstance(default, list) else float


def _literal(text: str) -> Any:
    try:
        return ast.literal_eval(text)
    except (ValueError, SyntaxError):
        return text


def _is_builtin(source: Any) -> bool:
    return inspect.isbuiltin(source) or type(source).__name__ in ("builtin_function_or_method", "instancemethod")
