"""Substance function graphs (value processors, pixel processors, dynamic parameter values),
evaluated with torch so that their result is differentiable in the values of their variables.

Representation (plain data, JSON-serialisable)::

    {"nodes": {ID: {"function": NAME, "inputs": {PORT: ID, ...}, "data": VALUE}, ...},
     "root": ID}

``ID`` is a string, ``NAME`` one of :data:`FUNCTIONS` (Substance's function names as stored in
.sbs files: ``const_float1``, ``get_float1``, ``add``, ``swizzle2``, ``ifelse``, ``samplelum``, ...),
``PORT`` one of the function's ports (``a``/``b``; ``x`` for lerp; ``condition``/``ifpath``/
``elsepath``; ``componentsin``/``componentslast``; ``vector``; ``theta``/``rho``; ``pos``;
``seqin``/``seqlast``; ``value``). ``data`` depends on the function:

- ``const_*``: the constant (number, list of numbers, bool or string); absent = zero / false / "";
- ``get_*`` and ``set``: the variable's name (an exposed parameter, or a system variable such as
  ``$pos``, ``$size``, ``$sizelog2``, ``$normalformat``);
- ``swizzleN``/``iswizzleN``: the list of N component indices;
- ``samplelum``/``samplecol``: ``{"input": INDEX, "filtering": 0 bilinear | 1 nearest}``.

Values are tensors whose last dimension holds the components (1 for a scalar, up to 4); leading
dimensions broadcast, so variables of shape (B, k) give a batch of B results and a ``$pos`` of shape
(N, H, W, 2) gives one result per pixel (the pixel processor). Integers and booleans are carried as
float tensors with integral / 0-1 values (``div`` of integers truncates); strings are Python strings.
``rand`` draws from ``torch.Generator().manual_seed(...)`` seeded by the evaluation's seed and the
node's id, so it is deterministic; the draw is a constant factor, so ``rand(a)`` is differentiable in ``a``.

Every malformed graph (unknown function, unknown port, dangling reference, cycle, wrong data) is a
DiffMatError raised by :func:`validate`, which :func:`evaluate` calls first.
"""
from __future__ import annotations

import json
import math
import zlib
from functools import lru_cache
from typing import Any, Callable, Mapping, Sequence

import torch

from ..errors import DiffMatError
from .common import broadcast_shape, sample_wrap

# re-exported by diffmat.functional under these prefixed names
__all__ = ["evaluate_function_graph", "validate_function_graph", "load_function_graph"]

MAX_NODES = 20000

SYSTEM_VARIABLES = ("$pos", "$size", "$sizelog2", "$normalformat", "$time", "$number", "$depth")

_BINARY = ("a", "b")
_UNARY = ("a", "value", "input")

# name -> allowed ports (first listed ports are evaluated first, which matters for `sequence`)
FUNCTIONS: dict[str, tuple[str, ...]] = {}
for _n in ("float1", "float2", "float3", "float4", "int1", "int2", "int3", "int4", "bool", "string"):
    FUNCTIONS[f"const_{_n}"] = ()
for _n in ("float1", "float2", "float3", "float4", "integer1", "integer2", "integer3", "integer4", "bool", "string"):
    FUNCTIONS[f"get_{_n}"] = ()
for _n in ("add", "sub", "mul", "mulscalar", "div", "mod", "dot", "cross", "and", "or", "eq", "noteq",
           "gt", "gteq", "lr", "lreq", "min", "max", "pow", "atan2"):
    FUNCTIONS[_n] = _BINARY
for _n in ("neg", "not", "abs", "floor", "ceil", "cos", "sin", "tan", "sqrt", "log", "log2", "exp", "pow2",
           "rand", "tofloat", "tofloat2", "tofloat3", "tofloat4", "toint1", "toint2", "toint3", "toint4",
           "passthrough", "normalize", "length"):
    FUNCTIONS[_n] = _UNARY
for _n in ("vector2", "vector3", "vector4", "ivector2", "ivector3", "ivector4"):
    FUNCTIONS[_n] = ("componentsin", "componentslast")
for _n in (1, 2, 3, 4):
    FUNCTIONS[f"swizzle{_n}"] = ("vector",)
    FUNCTIONS[f"iswizzle{_n}"] = ("vector",)
FUNCTIONS.update({
    "lerp": ("a", "b", "x"),
    "ifelse": ("condition", "ifpath", "elsepath"),
    "cartesian": ("theta", "rho"),
    "samplelum": ("pos",),
    "samplecol": ("pos",),
    "sequence": ("seqin", "seqlast"),
    "set": ("value",),
})

_FLOAT_FUNCS = {"cos", "sin", "tan", "sqrt", "log", "log2", "exp", "pow2", "atan2", "cartesian", "rand",
                "samplelum", "samplecol", "tofloat", "tofloat2", "tofloat3", "tofloat4", "pow", "normalize",
                "length"}
_BOOL_FUNCS = {"and", "or", "not", "eq", "noteq", "gt", "gteq", "lr", "lreq"}


def function_kind(name: str) -> str | None:
    """The value kind a function produces on its own: float, int, bool, string, or None when it
    follows its inputs (arithmetic)."""
    if name.startswith(("const_float", "get_float", "swizzle", "vector")) or name in _FLOAT_FUNCS:
        return "float"
    if name.startswith(("const_int", "get_integer", "iswizzle", "ivector", "toint")):
        return "int"
    if name in ("const_bool", "get_bool") or name in _BOOL_FUNCS:
        return "bool"
    if name in ("const_string", "get_string"):
        return "string"
    return None


def _err(msg: str) -> DiffMatError:
    return DiffMatError(f"function graph: {msg}")


def _is_number(x) -> bool:
    return isinstance(x, (int, float)) and not isinstance(x, bool) and math.isfinite(x)


def _check_data(nid: str, fn: str, data):
    if fn.startswith("const_"):
        if data is None:
            return
        if fn == "const_string":
            ok = isinstance(data, str)
        elif fn == "const_bool":
            ok = isinstance(data, (bool, int)) and not isinstance(data, float)
        else:
            ok = _is_number(data) or (isinstance(data, (list, tuple)) and 0 < len(data) <= 4
                                      and all(_is_number(v) for v in data))
        if not ok:
            raise _err(f"node {nid} ({fn}): bad constant {data!r}")
    elif fn.startswith("get_") or fn == "set":
        if not isinstance(data, str) or not data:
            raise _err(f"node {nid} ({fn}): expected a variable name, got {data!r}")
    elif fn.startswith(("swizzle", "iswizzle")):
        n = int(fn[-1])
        if (not isinstance(data, (list, tuple)) or len(data) != n
                or not all(isinstance(i, int) and not isinstance(i, bool) and 0 <= i < 4 for i in data)):
            raise _err(f"node {nid} ({fn}): expected {n} component index(es) in 0..3, got {data!r}")
    elif fn in ("samplelum", "samplecol"):
        if data is None:
            return
        if not isinstance(data, dict) or not all(
                k in ("input", "filtering") and isinstance(v, int) and not isinstance(v, bool) and 0 <= v < 64
                for k, v in data.items()):
            raise _err(f"node {nid} ({fn}): expected {{'input': int, 'filtering': int}}, got {data!r}")


def validate(graph: Any) -> dict:
    """Check a function graph's structure; returns it. DiffMatError on anything malformed."""
    if not isinstance(graph, dict) or not isinstance(graph.get("nodes"), dict):
        raise _err("expected a dict with 'nodes' and 'root'")
    nodes = graph["nodes"]
    if len(nodes) > MAX_NODES:
        raise _err(f"{len(nodes)} nodes is more than {MAX_NODES}")
    root = graph.get("root")
    if not isinstance(root, str) or root not in nodes:
        raise _err(f"root {root!r} is not a node")
    for nid, node in nodes.items():
        if not isinstance(nid, str) or not isinstance(node, dict):
            raise _err(f"node {nid!r}: expected a dict")
        fn = node.get("function")
        if fn not in FUNCTIONS:
            raise _err(f"node {nid}: unknown function {fn!r}")
        inputs = node.get("inputs", {}) or {}
        if not isinstance(inputs, dict):
            raise _err(f"node {nid} ({fn}): inputs must be a dict")
        for port, src in inputs.items():
            if port not in FUNCTIONS[fn]:
                raise _err(f"node {nid} ({fn}): unknown input port {port!r}")
            if not isinstance(src, str) or src not in nodes:
                raise _err(f"node {nid} ({fn}): input {port!r} refers to missing node {src!r}")
        _check_data(nid, fn, node.get("data"))
    # cycle check (iterative DFS from every node)
    state: dict[str, int] = {}
    for start in nodes:
        if start in state:
            continue
        stack = [(start, iter((nodes[start].get("inputs") or {}).values()))]
        state[start] = 1
        while stack:
            nid, it = stack[-1]
            nxt = next(it, None)
            if nxt is None:
                state[nid] = 2
                stack.pop()
            elif state.get(nxt) == 1:
                raise _err(f"cycle through node {nxt}")
            elif nxt not in state:
                state[nxt] = 1
                stack.append((nxt, iter((nodes[nxt].get("inputs") or {}).values())))
    return graph


def variables_of(graph: dict) -> set[str]:
    """Names read by the ``get_*`` nodes reachable from the root."""
    return {graph["nodes"][n].get("data") for n in _order(graph)
            if graph["nodes"][n]["function"].startswith("get_")}


def _order(graph: dict) -> list[str]:
    """Nodes reachable from the root, inputs before consumers (ports in declaration order)."""
    nodes, out, seen = graph["nodes"], [], set()
    stack = [(graph["root"], False)]
    while stack:
        nid, done = stack.pop()
        if done:
            out.append(nid)
            continue
        if nid in seen:
            continue
        seen.add(nid)
        stack.append((nid, True))
        inputs = nodes[nid].get("inputs") or {}
        ports = [p for p in FUNCTIONS[nodes[nid]["function"]] if p in inputs]
        for p in reversed(ports):
            if inputs[p] not in seen:
                stack.append((inputs[p], False))
    return out


def loads(text: str) -> dict:
    """A function graph from its JSON text, validated (cached by text)."""
    return _loads_cached(text)


@lru_cache(maxsize=256)
def _loads_cached(text: str) -> dict:
    try:
        graph = json.loads(text)
    except (TypeError, ValueError) as exc:
        raise _err(f"not valid JSON ({exc})") from None
    return validate(graph)


def dumps(graph: dict) -> str:
    """Compact, stable JSON text of a function graph."""
    return json.dumps(graph, sort_keys=True, separators=(",", ":"))


# ---- evaluation -------------------------------------------------------------------------------
class _V:
    """A value during evaluation: tensor (..., k) or str, and its kind."""

    __slots__ = ("t", "kind")

    def __init__(self, t, kind: str):
        self.t, self.kind = t, kind


def _cat(xs: Sequence[torch.Tensor]) -> torch.Tensor:
    lead = broadcast_shape(*(x.shape[:-1] for x in xs))
    return torch.cat([x.expand(*lead, x.shape[-1]) for x in xs], dim=-1)


def _as_tensor(value, like_device, dtype) -> torch.Tensor:
    if isinstance(value, torch.Tensor):
        t = value.to(device=like_device, dtype=dtype)
    elif isinstance(value, bool):
        t = torch.tensor([float(value)], device=like_device, dtype=dtype)
    else:
        t = torch.as_tensor(value, dtype=dtype, device=like_device)
    if t.dim() == 0:
        t = t.reshape(1)
    return t


def _sample(images, index: int, pos: torch.Tensor, filtering: int, lum: bool, dtype, device):
    img = images[index] if 0 <= index < len(images) else None
    if pos.shape[-1] < 2:
        pos = pos.expand(*pos.shape[:-1], 2)
    pos = pos[..., :2]
    if pos.dim() == 1:
        pos = pos.reshape(1, 1, 1, 2)
    elif pos.dim() == 2:
        pos = pos[:, None, None, :]
    elif pos.dim() == 3:
        pos = pos[None]
    if img is None:
        return torch.zeros(*pos.shape[:-1], 1 if lum else 4, device=device, dtype=dtype) + (
            0.0 if lum else torch.tensor([0.0, 0.0, 0.0, 1.0], device=device, dtype=dtype))
    img = img.to(dtype)
    if pos.shape[0] not in (1, img.shape[0]) and img.shape[0] != 1:
        raise _err(f"sampler: batch {pos.shape[0]} of positions against {img.shape[0]} images")
    out = sample_wrap(img, pos[..., 0], pos[..., 1], mode="nearest" if filtering == 1 else "bilinear")
    out = out.permute(0, 2, 3, 1)  # (B, H, W, C)
    if lum:
        return out if out.shape[-1] == 1 else out[..., :3].mean(-1, keepdim=True)
    if out.shape[-1] == 1:
        return torch.cat([out, out, out, torch.ones_like(out)], dim=-1)
    return out


def _seed_for(seed: int, nid: str) -> int:
    return (zlib.crc32(nid.encode("utf-8")) * 1000003 + int(seed)) & 0x7FFFFFFF


def evaluate(graph: dict, variables: Mapping[str, Any] | None = None, *, images: Sequence = (),
             seed: int = 0, device=None, dtype: torch.dtype = torch.float32, kind: bool = False):
    """Evaluate ``graph`` (validated first) and return the root's value.

    ``variables`` maps variable names to numbers, sequences or tensors (last dimension =
    components; leading dimensions broadcast). ``images`` are the NCHW images the samplers read.
    Returns a tensor of shape (..., k) (or a str for string results); with ``kind`` True, returns
    (value, kind) where kind is float, int, bool or string. An unset variable is a DiffMatError.
    """
    validate(graph)
    variables = dict(variables or {})
    nodes = graph["nodes"]
    if device is None:
        device = next((v.device for v in variables.values() if isinstance(v, torch.Tensor)), torch.device("cpu"))
    vals: dict[str, _V] = {}

    def arg(nid: str, port: str, node: dict) -> _V | None:
        src = (node.get("inputs") or {}).get(port)
        return vals[src] if src is not None else None

    for nid in _order(graph):
        node = nodes[nid]
        fn = node["function"]
        data = node.get("data")
        try:
            vals[nid] = _apply(fn, data, node, nid, arg, variables, images, seed, device, dtype)
        except DiffMatError:
            raise
        except (RuntimeError, IndexError, TypeError, ValueError) as exc:
            raise _err(f"node {nid} ({fn}): {exc}") from None
    out = vals[graph["root"]]
    return (out.t, out.kind) if kind else out.t


def _num(v: _V | None, what: str) -> torch.Tensor:
    if v is None:
        raise _err(f"{what}: input not connected")
    if v.kind == "string":
        raise _err(f"{what}: expected a number, got a string")
    return v.t


def _apply(fn, data, node, nid, arg, variables, images, seed, device, dtype) -> _V:
    def zeros(k):
        return torch.zeros(k, device=device, dtype=dtype)

    if fn.startswith("const_"):
        k = function_kind(fn)
        if fn == "const_string":
            return _V("" if data is None else data, "string")
        if fn == "const_bool":
            return _V(torch.tensor([float(bool(data))], device=device, dtype=dtype), "bool")
        n = int(fn[-1])
        if data is None:
            return _V(zeros(n), k)
        t = _as_tensor(data, device, dtype).reshape(-1)
        if t.numel() == 1 and n > 1:
            t = t.expand(n)
        return _V(t[:n].clone() if t.numel() >= n else torch.cat([t, zeros(n - t.numel())]), k)
    if fn.startswith("get_"):
        if data not in variables:
            raise _err(f"node {nid} ({fn}): variable {data!r} is not set")
        v = variables[data]
        k = function_kind(fn)
        if fn == "get_string":
            return _V(v if isinstance(v, str) else str(v), "string")
        if isinstance(v, str):
            raise _err(f"node {nid} ({fn}): variable {data!r} holds a string")
        t = _as_tensor(v, device, dtype)
        n = 1 if fn == "get_bool" else int(fn[-1])
        if t.shape[-1] != n:
            if t.shape[-1] == 1:
                t = t.expand(*t.shape[:-1], n)
            elif t.shape[-1] > n:
                t = t[..., :n]
            else:
                raise _err(f"node {nid} ({fn}): variable {data!r} has {t.shape[-1]} component(s), expected {n}")
        return _V(t, k)
    if fn == "set":
        v = arg(nid, "value", node)
        if v is None:
            raise _err(f"node {nid} (set): input not connected")
        variables[data] = v.t
        return v
    if fn == "sequence":
        v = arg(nid, "seqlast", node)
        if v is None:
            raise _err(f"node {nid} (sequence): seqlast not connected")
        return v
    if fn in ("samplelum", "samplecol"):
        pos = _num(arg(nid, "pos", node), f"node {nid} ({fn})")
        d = data or {}
        out = _sample(images, d.get("input", 0), pos, d.get("filtering", 0), fn == "samplelum", dtype, device)
        return _V(out, "float")
    if fn.startswith(("vector", "ivector")):
        a = _num(arg(nid, "componentsin", node), f"node {nid} ({fn})")
        b = _num(arg(nid, "componentslast", node), f"node {nid} ({fn})")
        out = _cat([a, b])
        n = int(fn[-1])
        if out.shape[-1] != n:
            raise _err(f"node {nid} ({fn}): components add up to {out.shape[-1]}, expected {n}")
        return _V(out, function_kind(fn))
    if fn.startswith(("swizzle", "iswizzle")):
        v = _num(arg(nid, "vector", node), f"node {nid} ({fn})")
        if max(data) >= v.shape[-1]:
            raise _err(f"node {nid} ({fn}): component {max(data)} of a {v.shape[-1]}-vector")
        return _V(v[..., list(data)], function_kind(fn))
    if fn == "ifelse":
        c = _num(arg(nid, "condition", node), f"node {nid} (ifelse)")
        a, b = arg(nid, "ifpath", node), arg(nid, "elsepath", node)
        if a is None or b is None:
            raise _err(f"node {nid} (ifelse): a path is not connected")
        if a.kind == "string" or b.kind == "string":
            return a if bool(c.reshape(-1)[0] > 0.5) else b
        cond = c[..., :1] > 0.5
        return _V(torch.where(cond, a.t, b.t), a.kind)
    if fn == "lerp":
        a, b, x = (_num(arg(nid, p, node), f"node {nid} (lerp)") for p in ("a", "b", "x"))
        return _V(a + x * (b - a), "float")
    if fn == "cartesian":
        th = _num(arg(nid, "theta", node), f"node {nid} (cartesian)")
        rho = _num(arg(nid, "rho", node), f"node {nid} (cartesian)")
        return _V(_cat([rho * torch.cos(th), rho * torch.sin(th)]), "float")
    if FUNCTIONS[fn] == _UNARY:
        v = next((arg(nid, p, node) for p in _UNARY if arg(nid, p, node) is not None), None)
        if fn == "rand":
            a = _num(v, f"node {nid} (rand)") if v is not None else torch.ones(1, device=device, dtype=dtype)
            g = torch.Generator().manual_seed(_seed_for(seed, nid))
            u = torch.rand(a.shape[-1], generator=g, dtype=torch.float64).to(device=device, dtype=dtype)
            return _V(a * u, "float")
        if v is None:
            raise _err(f"node {nid} ({fn}): input not connected")
        if fn == "passthrough":
            return v
        a = _num(v, f"node {nid} ({fn})")
        return _V(_UNARY_OPS[fn](a), function_kind(fn) or v.kind)
    # binary
    va, vb = arg(nid, "a", node), arg(nid, "b", node)
    if fn == "atan2" and va is not None and vb is None:
        return _V(_atan2_unary(_num(va, f"node {nid} (atan2)")), "float")
    if va is None or vb is None:
        raise _err(f"node {nid} ({fn}): input {'a' if va is None else 'b'} not connected")
    if fn in ("eq", "noteq") and (va.kind == "string" or vb.kind == "string"):
        same = va.t == vb.t if va.kind == vb.kind == "string" else False
        return _V(torch.tensor([float(same == (fn == "eq"))], device=device, dtype=dtype), "bool")
    a, b = _num(va, f"node {nid} ({fn})"), _num(vb, f"node {nid} ({fn})")
    integer = va.kind == "int" and vb.kind == "int"
    out = _binary(fn, a, b, integer)
    return _V(out, function_kind(fn) or ("int" if integer else va.kind if va.kind == vb.kind else "float"))


def _safe_div(a, b, integer):
    if integer:
        safe = torch.where(b == 0, torch.ones_like(b), b)
        return torch.where(b == 0, torch.zeros_like(a * b), torch.div(a, safe, rounding_mode="trunc"))
    return a / b


def _binary(fn, a, b, integer):
    if fn == "add":
        return a + b
    if fn == "sub":
        return a - b
    if fn in ("mul", "mulscalar"):
        return a * b
    if fn == "div":
        return _safe_div(a, b, integer)
    if fn == "mod":
        safe = torch.where(b == 0, torch.ones_like(b), b)
        return torch.where(b == 0, torch.zeros_like(a * b), torch.fmod(a, safe))
    if fn == "dot":
        return (a * b).sum(-1, keepdim=True)
    if fn == "cross":
        a, b = torch.broadcast_tensors(a, b)
        if a.shape[-1] != 3:
            raise _err("cross: expected 3-vectors")
        return torch.linalg.cross(a, b, dim=-1)
    if fn == "min":
        return torch.minimum(a, b)
    if fn == "max":
        return torch.maximum(a, b)
    if fn == "pow":
        return torch.pow(a, b)
    if fn == "atan2":
        return torch.atan2(a, b)
    if fn == "and":
        return ((a > 0.5) & (b > 0.5)).all(-1, keepdim=True).to(a.dtype)
    if fn == "or":
        return ((a > 0.5) | (b > 0.5)).all(-1, keepdim=True).to(a.dtype)
    cmp = {"eq": torch.eq, "noteq": torch.ne, "gt": torch.gt, "gteq": torch.ge, "lr": torch.lt,
           "lreq": torch.le}[fn]
    res = cmp(a, b)
    res = res.any(-1, keepdim=True) if fn == "noteq" else res.all(-1, keepdim=True)
    return res.to(a.dtype)


def _atan2_unary(a):
    if a.shape[-1] < 2:
        raise _err("atan2: expected a 2-vector")
    return torch.atan2(a[..., 1:2], a[..., 0:1])


_UNARY_OPS: dict[str, Callable] = {
    "neg": lambda a: -a,
    "not": lambda a: (a <= 0.5).to(a.dtype),
    "abs": torch.abs,
    "floor": torch.floor,
    "ceil": torch.ceil,
    "cos": torch.cos,
    "sin": torch.sin,
    "tan": torch.tan,
    "sqrt": lambda a: torch.sqrt(torch.clamp(a, min=0.0)),
    "log": lambda a: torch.log(torch.clamp(a, min=1e-30)),
    "log2": lambda a: torch.log2(torch.clamp(a, min=1e-30)),
    "exp": torch.exp,
    "pow2": lambda a: torch.pow(2.0, a),
    "tofloat": lambda a: a,
    "tofloat2": lambda a: a,
    "tofloat3": lambda a: a,
    "tofloat4": lambda a: a,
    "toint1": torch.trunc,
    "toint2": torch.trunc,
    "toint3": torch.trunc,
    "toint4": torch.trunc,
    "normalize": lambda a: a / torch.clamp(a.norm(dim=-1, keepdim=True), min=1e-12),
    "length": lambda a: a.norm(dim=-1, keepdim=True),
}


evaluate_function_graph = evaluate
validate_function_graph = validate
load_function_graph = loads
