"""Expressions that drive node parameters from a material's exposed parameters, written as Python
(``lerp(0.2, 0.9, get("wear"))``, ``get("scale") * 2``) and turned into Substance function graphs
(the dynamic values of a ``.sbs`` file, evaluated by ``diffmat.functional.function_graph``).

Each expression knows its component count (1–4), so the function names and type codes it produces
are the ones Substance writes: ``const_float4``, ``mulscalar`` for a vector times a scalar, etc.
"""
from __future__ import annotations

import itertools
from typing import Sequence


class Expr:
    """A node of a function graph: ``function`` applied to ``inputs`` (port -> Expr), with ``data``."""

    __slots__ = ("function", "inputs", "data", "size")

    def __init__(self, function: str, size: int, inputs: dict | None = None, data=None):
        self.function, self.size, self.inputs, self.data = function, size, dict(inputs or {}), data

    # arithmetic --------------------------------------------------------------------------
    def _binary(self, other, name: str, swap: bool = False) -> "Expr":
        other = as_expr(other)
        a, b = (other, self) if swap else (self, other)
        if a.size == b.size:
            return Expr(name, a.size, {"a": a, "b": b})
        if name == "mul" and 1 in (a.size, b.size):
            vec, scalar = (a, b) if b.size == 1 else (b, a)
            return Expr("mulscalar", vec.size, {"a": vec, "b": scalar})
        raise ValueError(f"cannot {name} a float{a.size} and a float{b.size}")

    def __add__(self, o): return self._binary(o, "add")
    def __radd__(self, o): return self._binary(o, "add", swap=True)
    def __sub__(self, o): return self._binary(o, "sub")
    def __rsub__(self, o): return self._binary(o, "sub", swap=True)
    def __mul__(self, o): return self._binary(o, "mul")
    def __rmul__(self, o): return self._binary(o, "mul", swap=True)
    def __truediv__(self, o): return self._binary(o, "div")
    def __rtruediv__(self, o): return self._binary(o, "div", swap=True)
    def __neg__(self): return Expr("neg", self.size, {"a": self})

    def graph(self) -> dict:
        """The plain-data function graph (``diffmat.functional.function_graph`` format)."""
        nodes: dict[str, dict] = {}
        ids: dict[int, str] = {}
        counter = itertools.count(1)

        def visit(e: Expr) -> str:
            if id(e) in ids:
                return ids[id(e)]
            inputs = {port: visit(src) for port, src in e.inputs.items()}
            key = ids[id(e)] = str(next(counter))
            node = {"function": e.function, "inputs": inputs}
            if e.data is not None:
                node["data"] = e.data
            nodes[key] = node
            return key

        return {"nodes": nodes, "root": visit(self)}


def as_expr(x) -> Expr:
    return x if isinstance(x, Expr) else const(x)


def const(value) -> Expr:
    """A constant: a number (float1) or a sequence of 2–4 numbers."""
    values = list(value) if isinstance(value, Sequence) else [value]
    if not 1 <= len(values) <= 4:
        raise ValueError(f"a constant has 1 to 4 components, not {len(values)}")
    data = float(values[0]) if len(values) == 1 else [float(v) for v in values]
    return Expr(f"const_float{len(values)}", len(values), data=data)


def get(name: str, size: int = 1) -> Expr:
    """The value of exposed float parameter ``name`` (``size`` components)."""
    return Expr(f"get_float{size}", size, data=name)


def lerp(a, b, x) -> Expr:
    """a + x (b - a); ``x`` a scalar."""
    a, b, x = as_expr(a), as_expr(b), as_expr(x)
    if a.size != b.size or x.size != 1:
        raise ValueError("lerp needs a and b of one size and a scalar weight")
    return Expr("lerp", a.size, {"a": a, "b": b, "x": x})


def minimum(a, b) -> Expr:
    a, b = as_expr(a), as_expr(b)
    return Expr("min", a.size, {"a": a, "b": b})


def maximum(a, b) -> Expr:
    a, b = as_expr(a), as_expr(b)
    return Expr("max", a.size, {"a": a, "b": b})


def clamp(x, lo, hi) -> Expr:
    return minimum(maximum(x, lo), hi)


def vector(*parts) -> Expr:
    """Concatenate scalars/vectors into one vector of 2–4 components (Substance's vectorN nodes)."""
    exprs = [as_expr(p) for p in parts]
    out = exprs[0]
    for nxt in exprs[1:]:
        size = out.size + nxt.size
        if size > 4:
            raise ValueError("a vector has at most 4 components")
        out = Expr(f"vector{size}", size, {"componentsin": out, "componentslast": nxt})
    return out


def gray4(x, alpha: float = 1.0) -> Expr:
    """A scalar spread into an RGBA level (x, x, x, alpha), as levels parameters take it."""
    x = as_expr(x)
    return vector(x, x, x, alpha)
