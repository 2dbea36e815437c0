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

A graph evaluated many times (a pixel processor's, a bound parameter's at every forward pass) is
compiled once (:func:`compile_graph`, or :func:`compiled` for JSON text): validated, ordered, and
turned into one closure per node with its function, data and ports resolved, so an evaluation
only runs the closures.
"""
from __future__ import annotations

import json
import math
import zlib
from dataclasses import dataclass
from functools import lru_cache
from typing import Any, Callable, Mapping, Sequence

import torch

from ..errors import DiffMatError
from .common import broadcast_shape, sample_wrap

# re-exported by diffmat.functional under these prefixed names
__all__ = ["evaluate_function_graph", "validate_function_graph", "load_function_graph", "compile_function_graph",
           "reachable_order"]

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
for _k in (1, 2, 3, 4):
    FUNCTIONS[f"swizzle{_k}"] = ("vector",)
    FUNCTIONS[f"iswizzle{_k}"] = ("vector",)
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


def _own_kind(name: str) -> str:
    """The kind of a function that produces one on its own (constants, getters, vectors...)."""
    kind = function_kind(name)
    assert kind is not None, name
    return kind


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
        _check_node(nid, node, nodes)
    _check_acyclic(nodes)
    return graph


def _check_node(nid, node, nodes: dict):
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


def _check_acyclic(nodes: dict):
    """DiffMatError on a cycle (iterative depth-first search from every node)."""
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


def variables_of(graph: dict) -> set[str]:
    """Names read by the ``get_*`` nodes reachable from the root."""
    return {graph["nodes"][n].get("data") for n in reachable_order(graph)
            if graph["nodes"][n]["function"].startswith("get_")}


def reachable_order(graph: dict) -> list[str]:
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


# ---- compilation: one closure per node, built once per graph -----------------------------------
@dataclass
class _Env:
    """What one evaluation shares: the variables (``set`` writes them), sampled images, seed,
    device and dtype."""

    variables: dict[str, Any]
    images: Sequence
    seed: int
    device: Any
    dtype: torch.dtype

    def zeros(self, k: int) -> torch.Tensor:
        return torch.zeros(k, device=self.device, dtype=self.dtype)


_Inputs = Mapping[str, _V]             # a node's connected inputs by port
_Op = Callable[[_Env, _Inputs], _V]


class CompiledGraph:
    """A function graph (validated) compiled to one closure per node in evaluation order, so an
    evaluation runs them without re-validating, re-sorting or dispatching on function names.
    ``variables`` are the names its ``get_*`` nodes read."""

    def __init__(self, graph: dict):
        validate(graph)
        nodes = graph["nodes"]
        order = reachable_order(graph)
        self.variables = {nodes[n].get("data") for n in order if nodes[n]["function"].startswith("get_")}
        self._root = graph["root"]
        self._steps = [(nid, nodes[nid]["function"], tuple((nodes[nid].get("inputs") or {}).items()),
                        _compile_node(nid, nodes[nid])) for nid in order]

    def __call__(self, variables: Mapping[str, Any] | None = None, *, images: Sequence = (), seed: int = 0,
                 device=None, dtype: torch.dtype = torch.float32, kind: bool = False):
        """Evaluate; the arguments and the result are those of :func:`evaluate`."""
        env = _Env(dict(variables or {}), images, seed, device, dtype)
        if device is None:
            env.device = next((v.device for v in env.variables.values() if isinstance(v, torch.Tensor)),
                              torch.device("cpu"))
        vals: dict[str, _V] = {}
        for nid, fn, inputs, op in self._steps:
            try:
                vals[nid] = op(env, {port: vals[src] for port, src in inputs})
            except DiffMatError:
                raise
            except (RuntimeError, IndexError, TypeError, ValueError) as exc:
                raise _err(f"node {nid} ({fn}): {exc}") from None
        out = vals[self._root]
        return (out.t, out.kind) if kind else out.t


def compile_graph(graph: dict) -> CompiledGraph:
    """Validate ``graph`` and compile it (see :class:`CompiledGraph`)."""
    return CompiledGraph(graph)


@lru_cache(maxsize=256)
def compiled(text: str) -> CompiledGraph:
    """The compiled function graph of JSON text (cached by text, like :func:`loads`)."""
    return CompiledGraph(loads(text))


def evaluate(graph: dict, variables: Mapping[str, Any] | None = None, *, images: Sequence = (),
             seed: int = 0, device=None, dtype: torch.dtype = torch.float32, kind: bool = False):
    """Evaluate ``graph`` (validated first) and return the root's value.

    ``variables`` maps variable names to numbers, sequences or tensors (last dimension =
    components; leading dimensions broadcast). ``images`` are the NCHW images the samplers read.
    Returns a tensor of shape (..., k) (or a str for string results); with ``kind`` True, returns
    (value, kind) where kind is float, int, bool or string. An unset variable is a DiffMatError.
    A graph evaluated repeatedly is better compiled once (:func:`compile_graph`, :func:`compiled`).
    """
    return CompiledGraph(graph)(variables, images=images, seed=seed, device=device, dtype=dtype, kind=kind)


def _num(v: _V | None, what: str) -> torch.Tensor:
    if v is None:
        raise _err(f"{what}: input not connected")
    if v.kind == "string":
        raise _err(f"{what}: expected a number, got a string")
    return v.t


def _compile_node(nid: str, node: dict) -> _Op:
    fn, data = node["function"], node.get("data")
    where = f"node {nid} ({fn})"
    for prefixes, make in _COMPILERS:
        if fn.startswith(prefixes):
            return make(nid, fn, data, where)
    if FUNCTIONS[fn] == _UNARY:
        return _compile_unary(nid, fn, node, where)
    return _compile_binary(fn, where)


def _compile_const(nid: str, fn: str, data, where: str) -> _Op:
    kind = _own_kind(fn)
    if fn == "const_string":
        text = "" if data is None else data
        return lambda env, ins: _V(text, "string")
    if fn == "const_bool":
        flag = float(bool(data))
        return lambda env, ins: _V(torch.tensor([flag], device=env.device, dtype=env.dtype), "bool")
    n = int(fn[-1])

    def const(env: _Env, ins: _Inputs) -> _V:
        if data is None:
            return _V(env.zeros(n), kind)
        t = _as_tensor(data, env.device, env.dtype).reshape(-1)
        if t.numel() == 1 and n > 1:
            t = t.expand(n)
        return _V(t[:n].clone() if t.numel() >= n else torch.cat([t, env.zeros(n - t.numel())]), kind)
    return const


def fit_components(t: torch.Tensor, n: int, what: str, fill=None) -> torch.Tensor:
    """``t`` (last axis: its components) made ``n`` components wide, as Substance converts between
    vector types: one component fills them all and extra ones are dropped. Missing ones come from
    ``fill`` (a number or the components of a default: a float3 colour bound to an RGBA parameter
    keeps the default's alpha); without ``fill`` they are a DiffMatError naming ``what``."""
    m = t.shape[-1]
    if m == n:
        return t
    if m == 1:
        return t.expand(*t.shape[:-1], n)
    if m > n:
        return t[..., :n]
    if fill is None:
        raise _err(f"{what} has {m} component(s), expected {n}")
    base = torch.as_tensor(fill, dtype=t.dtype, device=t.device).reshape(-1)
    if base.numel() == 1:
        base = base.expand(n)
    elif base.numel() < n:
        base = torch.cat([base, base.new_zeros(n - base.numel())])
    return torch.cat([t, base[m:n].expand(*t.shape[:-1], n - m)], dim=-1)


def _compile_get(nid: str, fn: str, data, where: str) -> _Op:
    kind = _own_kind(fn)
    n = 1 if fn in ("get_bool", "get_string") else int(fn[-1])

    def get(env: _Env, ins: _Inputs) -> _V:
        if data not in env.variables:
            raise _err(f"{where}: variable {data!r} is not set")
        v = env.variables[data]
        if fn == "get_string":
            return _V(v if isinstance(v, str) else str(v), "string")
        if isinstance(v, str):
            raise _err(f"{where}: variable {data!r} holds a string")
        return _V(fit_components(_as_tensor(v, env.device, env.dtype), n, f"{where}: variable {data!r}"), kind)
    return get


def _compile_pass_on(nid: str, fn: str, data, where: str) -> _Op:
    """``set`` (stores its ``value`` input in variable ``data``) and ``sequence``: both return
    their input (``value``, ``seqlast``)."""
    port, missing = ("value", "input") if fn == "set" else ("seqlast", "seqlast")

    def pass_on(env: _Env, ins: _Inputs) -> _V:
        v = ins.get(port)
        if v is None:
            raise _err(f"node {nid} ({fn}): {missing} not connected")
        if fn == "set":
            env.variables[data] = v.t
        return v
    return pass_on


def _compile_sampler(nid: str, fn: str, data, where: str) -> _Op:
    d = data or {}
    index, filtering, lum = d.get("input", 0), d.get("filtering", 0), fn == "samplelum"

    def sample(env: _Env, ins: _Inputs) -> _V:
        pos = _num(ins.get("pos"), where)
        return _V(_sample(env.images, index, pos, filtering, lum, env.dtype, env.device), "float")
    return sample


def _compile_vector(nid: str, fn: str, data, where: str) -> _Op:
    n, kind = int(fn[-1]), _own_kind(fn)

    def vector(env: _Env, ins: _Inputs) -> _V:
        out = _cat([_num(ins.get("componentsin"), where), _num(ins.get("componentslast"), where)])
        if out.shape[-1] != n:
            raise _err(f"{where}: components add up to {out.shape[-1]}, expected {n}")
        return _V(out, kind)
    return vector


def _compile_swizzle(nid: str, fn: str, data, where: str) -> _Op:
    kind, index, top = _own_kind(fn), list(data), max(data)

    def swizzle(env: _Env, ins: _Inputs) -> _V:
        v = _num(ins.get("vector"), where)
        if top >= v.shape[-1]:
            raise _err(f"{where}: component {top} of a {v.shape[-1]}-vector")
        return _V(v[..., index], kind)
    return swizzle


def _compile_ifelse(nid: str, fn: str, data, where: str) -> _Op:
    def ifelse(env: _Env, ins: _Inputs) -> _V:
        c = _num(ins.get("condition"), f"node {nid} (ifelse)")
        a, b = ins.get("ifpath"), ins.get("elsepath")
        if a is None or b is None:
            raise _err(f"node {nid} (ifelse): a path is not connected")
        if a.kind == "string" or b.kind == "string":
            return a if bool(c.reshape(-1)[0] > 0.5) else b
        return _V(torch.where(c[..., :1] > 0.5, a.t, b.t), a.kind)
    return ifelse


def _compile_lerp(nid: str, fn: str, data, where: str) -> _Op:
    def lerp(env: _Env, ins: _Inputs) -> _V:
        a, b, x = (_num(ins.get(p), f"node {nid} (lerp)") for p in ("a", "b", "x"))
        return _V(a + x * (b - a), "float")
    return lerp


def _compile_cartesian(nid: str, fn: str, data, where: str) -> _Op:
    def cartesian(env: _Env, ins: _Inputs) -> _V:
        th = _num(ins.get("theta"), f"node {nid} (cartesian)")
        rho = _num(ins.get("rho"), f"node {nid} (cartesian)")
        return _V(_cat([rho * torch.cos(th), rho * torch.sin(th)]), "float")
    return cartesian


def _compile_unary(nid: str, fn: str, node: dict, where: str) -> _Op:
    port = next((p for p in _UNARY if p in (node.get("inputs") or {})), None)
    if fn == "rand":
        return _compile_rand(nid, port)
    kind = function_kind(fn)

    def unary(env: _Env, ins: _Inputs) -> _V:
        v = ins.get(port) if port is not None else None
        if v is None:
            raise _err(f"{where}: input not connected")
        if fn == "passthrough":
            return v
        return _V(_UNARY_OPS[fn](_num(v, where)), kind or v.kind)
    return unary


def _compile_rand(nid: str, port: str | None) -> _Op:
    """``rand(a)``: ``a`` times a uniform draw seeded by the evaluation's seed and the node's id."""
    def rand(env: _Env, ins: _Inputs) -> _V:
        v = ins.get(port) if port is not None else None
        a = _num(v, f"node {nid} (rand)") if v is not None else torch.ones(1, device=env.device, dtype=env.dtype)
        g = torch.Generator().manual_seed(_seed_for(env.seed, nid))
        u = torch.rand(a.shape[-1], generator=g, dtype=torch.float64).to(device=env.device, dtype=env.dtype)
        return _V(a * u, "float")
    return rand


def _compile_binary(fn: str, where: str) -> _Op:
    kind, op = function_kind(fn), _BINARY_OPS[fn]

    def binary(env: _Env, ins: _Inputs) -> _V:
        va, vb = ins.get("a"), ins.get("b")
        if fn == "atan2" and va is not None and vb is None:
            return _V(_atan2_unary(_num(va, where)), "float")
        if va is None or vb is None:
            raise _err(f"{where}: input {'a' if va is None else 'b'} not connected")
        if fn in ("eq", "noteq") and (va.kind == "string" or vb.kind == "string"):
            same = va.t == vb.t if va.kind == vb.kind == "string" else False
            return _V(torch.tensor([float(same == (fn == "eq"))], device=env.device, dtype=env.dtype), "bool")
        a, b = _num(va, where), _num(vb, where)
        integer = va.kind == "int" and vb.kind == "int"
        return _V(op(a, b, integer), kind or ("int" if integer else va.kind if va.kind == vb.kind else "float"))
    return binary


_COMPILERS: tuple[tuple[tuple[str, ...], Callable[[str, str, Any, str], _Op]], ...] = (
    (("const_",), _compile_const),
    (("get_",), _compile_get),
    (("set", "sequence"), _compile_pass_on),
    (("samplelum", "samplecol"), _compile_sampler),
    (("vector", "ivector"), _compile_vector),
    (("swizzle", "iswizzle"), _compile_swizzle),
    (("ifelse",), _compile_ifelse),
    (("lerp",), _compile_lerp),
    (("cartesian",), _compile_cartesian),
)


def _safe_div(a, b, integer):
    if integer:
        safe = torch.where(b == 0, torch.ones_like(b), b)
        return torch.where(b == 0, torch.zeros_like(a * b), torch.div(a, safe, rounding_mode="trunc"))
    return a / b


def _mod(a, b, integer):
    safe = torch.where(b == 0, torch.ones_like(b), b)
    return torch.where(b == 0, torch.zeros_like(a * b), torch.fmod(a, safe))


def _cross(a, b, integer):
    a, b = torch.broadcast_tensors(a, b)
    if a.shape[-1] != 3:
        raise _err("cross: expected 3-vectors")
    return torch.linalg.cross(a, b, dim=-1)


def _compare(cmp: Callable, reduce_any: bool) -> Callable:
    """A comparison reduced over the components: all of them, or any for ``noteq``."""
    def compare(a, b, integer):
        res = cmp(a, b)
        res = res.any(-1, keepdim=True) if reduce_any else res.all(-1, keepdim=True)
        return res.to(a.dtype)
    return compare


_BINARY_OPS: dict[str, Callable] = {
    "add": lambda a, b, integer: a + b,
    "sub": lambda a, b, integer: a - b,
    "mul": lambda a, b, integer: a * b,
    "mulscalar": lambda a, b, integer: a * b,
    "div": _safe_div,
    "mod": _mod,
    "dot": lambda a, b, integer: (a * b).sum(-1, keepdim=True),
    "cross": _cross,
    "min": lambda a, b, integer: torch.minimum(a, b),
    "max": lambda a, b, integer: torch.maximum(a, b),
    "pow": lambda a, b, integer: torch.pow(a, b),
    "atan2": lambda a, b, integer: torch.atan2(a, b),
    "and": lambda a, b, integer: ((a > 0.5) & (b > 0.5)).all(-1, keepdim=True).to(a.dtype),
    "or": lambda a, b, integer: ((a > 0.5) | (b > 0.5)).all(-1, keepdim=True).to(a.dtype),
    "eq": _compare(torch.eq, False),
    "noteq": _compare(torch.ne, True),
    "gt": _compare(torch.gt, False),
    "gteq": _compare(torch.ge, False),
    "lr": _compare(torch.lt, False),
    "lreq": _compare(torch.le, False),
}


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
compile_function_graph = compile_graph
validate_function_graph = validate
load_function_graph = loads
