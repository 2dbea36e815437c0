"""Decoding .sbs scalar values: ``<x v="..."/>`` (and the old ``<x><value v="..."/></x>`` form),
and the typed constant elements (``constantValueFloat1..4``, ``constantValueInt32``/``Int1..4``,
``constantValueBool``, ``constantValueString``)."""
from __future__ import annotations

import math
from dataclasses import dataclass

from ..errors import BlenderMatchError

MAX_STRING = 4096


class BadValue(BlenderMatchError):
    """A value that cannot be decoded; the caller falls back to a default and reports it."""


class ClampedValue(BadValue):
    """An integer past its parameter's range: the caller uses ``value``, the nearest one in range
    (Substance takes slider ranges as hints, so the file's value is meant), and reports it."""

    def __init__(self, message: str, value: int):
        super().__init__(message)
        self.value = value


@dataclass(frozen=True)
class Value:
    """A decoded constant: ``kind`` float | int | bool | string; ``value`` a tuple of numbers
    (``n`` components), a bool or a str."""

    kind: str
    n: int
    value: object

    def numbers(self) -> list:
        if self.kind in ("float", "int"):
            assert isinstance(self.value, tuple)  # numbers are always decoded to a tuple
            return list(self.value)
        if self.kind == "bool":
            return [1 if self.value else 0]
        raise BadValue("a string where a number is expected")

    def python(self):
        """The plain Python value: a number, a list of numbers, a bool or a str."""
        if self.kind in ("float", "int"):
            return self.value[0] if self.n == 1 else list(self.value)
        return self.value


# tag -> (kind, components)
CONSTANT_TAGS = {
    "constantValueFloat": ("float", 1), "constantValueFloat1": ("float", 1),
    "constantValueFloat2": ("float", 2), "constantValueFloat3": ("float", 3),
    "constantValueFloat4": ("float", 4),
    "constantValueInt32": ("int", 1), "constantValueInt1": ("int", 1), "constantValueInt": ("int", 1),
    "constantValueInt2": ("int", 2), "constantValueInt3": ("int", 3), "constantValueInt4": ("int", 4),
    "constantValueBool": ("bool", 1), "constantValueString": ("string", 1),
}

IMAGE_TYPES = {1: 4, 2: 1, 3: None}  # type code -> channels (None = either)


def get_v(el) -> str | None:
    """The value of an element: its ``v`` attribute, or its child ``<value v=...>`` (old files)."""
    if el is None:
        return None
    v = el.get("v")
    if v is None:
        child = el.find("value")
        if child is not None:
            v = child.get("v")
    return v


def child_v(el, tag: str) -> str | None:
    return get_v(el.find(tag)) if el is not None else None


def to_int(text, what: str = "integer") -> int:
    try:
        x = int(str(text).strip())
    except (TypeError, ValueError):
        try:
            f = float(str(text).strip())
        except (TypeError, ValueError):
            raise BadValue(f"bad {what} {str(text)[:40]!r}") from None
        if not math.isfinite(f) or f != int(f):
            raise BadValue(f"bad {what} {str(text)[:40]!r}") from None
        x = int(f)
    if x >= 2 ** 31 and x < 2 ** 32:
        x -= 2 ** 32  # stored unsigned
    if abs(x) > 2 ** 53:
        raise BadValue(f"{what} {x} is out of range")
    return x


def to_float(text) -> float:
    try:
        x = float(str(text).strip())
    except (TypeError, ValueError):
        raise BadValue(f"bad number {str(text)[:40]!r}") from None
    if not math.isfinite(x) or abs(x) > 1e30:
        raise BadValue(f"number {str(text)[:40]!r} is not finite")
    return x


def decode_text(kind: str, n: int, text: str | None) -> Value:
    if text is None:
        raise BadValue("missing value")
    if kind == "string":
        if len(text) > MAX_STRING:
            raise BadValue("string too long")
        return Value("string", 1, text)
    parts = text.replace(",", " ").split()
    if kind == "bool":
        if len(parts) != 1:
            raise BadValue(f"bad boolean {text[:40]!r}")
        low = parts[0].lower()
        if low in ("true", "false"):
            return Value("bool", 1, low == "true")
        return Value("bool", 1, to_int(parts[0], "boolean") != 0)
    if len(parts) != n:
        raise BadValue(f"expected {n} component(s), got {text[:40]!r}")
    if kind == "int":
        return Value("int", n, tuple(to_int(p) for p in parts))
    return Value("float", n, tuple(to_float(p) for p in parts))


def decode_constant(el) -> Value:
    """Decode one ``constantValue*`` element."""
    spec = CONSTANT_TAGS.get(el.tag) if isinstance(el.tag, str) else None
    if spec is None:
        raise BadValue(f"unknown value element {str(el.tag)[:40]!r}")
    return decode_text(spec[0], spec[1], get_v(el))


def decode_container(el) -> Value:
    """Decode the single constant inside a ``paramValue``/``defaultValue``/``constantValue``."""
    if el is None:
        raise BadValue("missing value")
    for child in el:
        if isinstance(child.tag, str) and child.tag in CONSTANT_TAGS:
            return decode_constant(child)
    raise BadValue("no constant value")
