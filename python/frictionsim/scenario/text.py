"""Words of the scenario errors: dotted key paths, articles, TOML type names."""

from __future__ import annotations

from typing import Any


def join(prefix: str, key: str) -> str:
    """The dotted path of ``key`` below ``prefix`` ("" at the top level)."""
    return f"{prefix}.{key}" if prefix else key


def article(word: str) -> str:
    """"a" or "an" before ``word``."""
    return "an" if word[:1] in "aeiou" else "a"


def type_name(value: Any) -> str:
    """The TOML name of a value's type: boolean, integer, float, string, array, table."""
    if isinstance(value, bool):
        return "boolean"
    return {int: "integer", float: "float", str: "string", list: "array", dict: "table"}.get(type(value),
                                                                                              type(value).__name__)
