"""Function graphs of a .sbs file (``dynamicValue``, pixel/value processor functions) in the
engine's plain-data format (``diffmat.functional.function_graph``), and the operations the
translator needs on them: substitution of variables (an exposed parameter by its runtime getter,
a sub-graph's parameter by the instance's value, a value pin by the value processor feeding it),
renumbering, constant folding.

Everything coming from the file is validated here: node ids are renumbered, function names must
be in the engine's table, ports must be the function's ports, data must be numbers, validated
names or index lists. Anything else makes the conversion fail (the caller falls back to a default).
"""
from __future__ import annotations

import re

import torch

from ..diffmat.errors import DiffMatError
from ..diffmat.functional import function_graph as fg_engine
from ..errors import BlenderMatchError
from .runtime import fit_components
from .values import BadValue, Value, decode_container, get_v

MAX_FUNCTION_NODES = 2000
_UID = re.compile(r"^-?[0-9]{1,24}$")


class FunctionError(BlenderMatchError):
    """A function graph the translator cannot use (unsupported function, malformed)."""


def _python(value: Value):
    return value.python()


def parse_dynamic(el) -> dict:
    """Convert a ``dynamicValue`` (or any element with ``rootnode`` + ``paramNodes``) to a function
    graph whose ``get_*`` nodes still hold the file's variable names."""
    root = get_v(el.find("rootnode"))
    nodes: dict[str, dict] = {}
    pnodes = el.findall("paramNodes/paramNode")
    if len(pnodes) > MAX_FUNCTION_NODES:
        raise FunctionError(f"function graph of {len(pnodes)} nodes")
    for pn in pnodes:
        uid = get_v(pn.find("uid"))
        if uid is None or not _UID.match(uid):
            raise FunctionError("function node without a valid uid")
        if uid in nodes:
            raise FunctionError(f"duplicate function node uid {uid}")
        fn = get_v(pn.find("function"))
        if fn not in fg_engine.FUNCTIONS:
            raise FunctionError(f"unsupported function {str(fn)[:40]!r}")
        inputs = {}
        conns = pn.findall("connections/connection") + pn.findall("connexions/connexion")
        for c in conns:
            port, src = get_v(c.find("identifier")), get_v(c.find("connRef"))
            if port not in fg_engine.FUNCTIONS[fn]:
                raise FunctionError(f"function {fn}: unknown input {str(port)[:40]!r}")
            if src is None or not _UID.match(src):
                raise FunctionError(f"function {fn}: bad connection")
            inputs[port] = src
        node: dict = {"function": fn, "inputs": inputs}
        data = _parse_data(fn, pn)
        if data is not None:
            node["data"] = data
        nodes[uid] = node
    if root not in nodes:
        raise FunctionError("function graph without a valid root node")
    for uid, node in nodes.items():
        for src in node["inputs"].values():
            if src not in nodes:
                raise FunctionError(f"function node {uid} reads missing node {src}")
    graph = {"nodes": nodes, "root": root}
    try:
        fg_engine.validate(graph)
    except DiffMatError as exc:
        raise FunctionError(str(exc)) from None
    return compact(graph)


def _parse_data(fn: str, pn):
    datas = pn.findall("funcDatas/funcData")
    if not datas:
        if fn.startswith(("get_", "swizzle", "iswizzle")) or fn == "set":
            raise FunctionError(f"function {fn}: missing data")
        return None
    try:
        if fn in ("samplelum", "samplecol"):
            out = {}
            for d in datas:
                name = (get_v(d.find("name")) or "").lower()
                v = decode_container(d.find("constantValue")).numbers()
                key = "filtering" if "filter" in name else "input"
                out[key] = int(v[0])
            return out if all(0 <= v < 64 for v in out.values()) else None
        d = next((d for d in datas if get_v(d.find("name")) == fn), datas[0])
        value = decode_container(d.find("constantValue"))
    except (BadValue, ValueError) as exc:
        raise FunctionError(f"function {fn}: {exc}") from None
    if fn.startswith(("swizzle", "iswizzle")):
        idx = [int(x) for x in value.numbers()]
        n = int(fn[-1])
        return fit_components(idx, n)
    if fn.startswith("get_") or fn == "set":
        if value.kind != "string" or not value.value:
            raise FunctionError(f"function {fn}: expected a variable name")
        return value.value
    if fn == "const_string":
        return value.value if value.kind == "string" else None
    if fn == "const_bool":
        return bool(value.numbers()[0]) if value.kind != "string" else None
    if fn.startswith("const_"):
        nums = value.numbers()
        nums = fit_components(nums, int(fn[-1]))
        return nums[0] if len(nums) == 1 else nums
    return None


def compact(graph: dict) -> dict:
    """Keep the nodes reachable from the root, renumbered "0", "1", ... inputs first."""
    order = fg_engine.reachable_order(graph)
    names = {old: str(i) for i, old in enumerate(order)}
    nodes = {}
    for old in order:
        node = graph["nodes"][old]
        new = {"function": node["function"],
               "inputs": {p: names[s] for p, s in sorted((node.get("inputs") or {}).items())}}
        if "data" in node:
            new["data"] = node["data"]
        nodes[names[old]] = new
    return {"nodes": nodes, "root": names[graph["root"]]}


def constant_graph(fn: str, value) -> dict:
    """A one-node graph ``fn`` (a ``get_*`` function name, telling the type) returning ``value``
    (a Value, a number, a list or a str)."""
    if isinstance(value, Value):
        value = value.python()
    if fn == "get_string" or isinstance(value, str):
        return {"nodes": {"0": {"function": "const_string", "inputs": {}, "data": str(value)}}, "root": "0"}
    if fn == "get_bool":
        v = value[0] if isinstance(value, (list, tuple)) else value
        return {"nodes": {"0": {"function": "const_bool", "inputs": {}, "data": bool(v)}}, "root": "0"}
    n = int(fn[-1]) if fn[-1].isdigit() else 1
    nums = list(value) if isinstance(value, (list, tuple)) else [value]
    nums = fit_components([float(x) if not fn.startswith("get_integer") else int(x) for x in nums], n,
                          _widening_fill(n))
    const = ("const_int" if fn.startswith("get_integer") else "const_float") + str(n)
    return {"nodes": {"0": {"function": const, "inputs": {}, "data": nums[0] if n == 1 else nums}}, "root": "0"}


def getter(kind: str, n: int, name: str) -> dict:
    """A one-node graph reading variable ``name`` of type (kind, n)."""
    fn = {"float": f"get_float{n}", "int": f"get_integer{n}", "bool": "get_bool", "string": "get_string"}[kind]
    return {"nodes": {"0": {"function": fn, "inputs": {}, "data": name}}, "root": "0"}


def _widening_fill(n: int) -> list:
    """The components a vector widened to ``n`` gets, as Substance converts: 0, and an alpha of 1
    for a 4-vector (a float3 colour into a float4 one is opaque)."""
    return [0] * (n - 1) + [1] if n == 4 else [0] * n


_WIDTH_ONE = {"tofloat", "dot", "length", "samplelum", "atan2", "const_bool", "get_bool", "const_string",
              "get_string", "and", "or", "not", "eq", "noteq", "gt", "gteq", "lr", "lreq"}
_WIDTH_FIXED = {"cross": 3, "cartesian": 2, "samplecol": 4}
_WIDTH_OF_INPUT = {"ifelse": ("ifpath", "elsepath"), "sequence": ("seqlast",), "mulscalar": ("a",)}
_WIDTH_NAMED = ("const_", "get_", "vector", "ivector", "swizzle", "iswizzle", "tofloat", "toint")


def result_width(graph: dict) -> int | None:
    """How many components a function graph returns, read from the function names (``get_float3``,
    ``swizzle2``...) and, for arithmetic, from the widest input; None when it cannot be told."""
    widths: dict[str, int | None] = {}
    for nid in fg_engine.reachable_order(graph):  # inputs before their consumers
        node = graph["nodes"][nid]
        fn, inputs = node["function"], node.get("inputs") or {}
        if fn in _WIDTH_ONE:
            widths[nid] = 1
        elif fn in _WIDTH_FIXED:
            widths[nid] = _WIDTH_FIXED[fn]
        elif fn.startswith(_WIDTH_NAMED) and fn[-1].isdigit():
            widths[nid] = int(fn[-1])
        else:
            found = [widths.get(inputs[p]) for p in _WIDTH_OF_INPUT.get(fn, tuple(inputs)) if p in inputs]
            widths[nid] = max(found) if found and None not in found else None  # type: ignore[type-var]
    return widths.get(graph["root"])


def fit_width(sub: dict, getter_fn: str) -> dict:
    """``sub`` (a function graph substituted for the ``getter_fn`` node) made as wide as the getter
    reads, as Substance converts between vector types: one component fills them all, extra ones are
    dropped, missing ones are 0 (alpha 1). A parameter can be given a value of another width than
    its declaration: an instance's float3 colour for a sub-graph's float4 parameter, a float4 for a
    float1..."""
    if not getter_fn[-1].isdigit():
        return sub
    n, m = int(getter_fn[-1]), result_width(sub)
    if m is None or m == n:
        return sub
    integer = getter_fn.startswith("get_integer")
    nodes, root = dict(sub["nodes"]), sub["root"]
    if m == 1 or m > n:
        fit = {"function": ("iswizzle" if integer else "swizzle") + str(n), "inputs": {"vector": root},
               "data": [0] * n if m == 1 else list(range(n))}
    else:
        rest = _widening_fill(n)[m:]
        nodes["fill"] = {"function": ("const_int" if integer else "const_float") + str(n - m), "inputs": {},
                         "data": rest[0] if len(rest) == 1 else rest}
        fit = {"function": ("ivector" if integer else "vector") + str(n),
               "inputs": {"componentsin": root, "componentslast": "fill"}}
    nodes["fit"] = fit
    return {"nodes": nodes, "root": "fit"}


def substitute(graph: dict, env: dict) -> dict:
    """Replace every ``get_*`` node whose variable is in ``env`` by ``env[variable]``: a function
    graph, a Value, or a plain constant (shaped by the getter's type)."""
    nodes: dict[str, dict] = {}
    remap: dict[str, str] = {}
    for nid in fg_engine.reachable_order(graph):
        node = graph["nodes"][nid]
        fn, data = node["function"], node.get("data")
        if fn.startswith("get_") and isinstance(data, str) and data in env:
            sub = env[data]
            if not isinstance(sub, dict):
                sub = constant_graph(fn, sub)
            elif sub["nodes"][sub["root"]]["function"].startswith("const_") and len(sub["nodes"]) == 1:
                sub = constant_graph(fn, sub["nodes"][sub["root"]].get("data", 0))
            else:
                sub = fit_width(sub, fn)
            prefix = f"{nid}_"
            for sid, snode in sub["nodes"].items():
                inputs = snode.get("inputs") or {}
                nodes[prefix + sid] = {**snode, "inputs": {p: prefix + s for p, s in inputs.items()}}
            remap[nid] = prefix + sub["root"]
        else:
            nodes[nid] = dict(node)
    for node in nodes.values():
        node["inputs"] = {p: remap.get(s, s) for p, s in (node.get("inputs") or {}).items()}
    out = {"nodes": nodes, "root": remap.get(graph["root"], graph["root"])}
    if len(nodes) > MAX_FUNCTION_NODES * 4:
        raise FunctionError("function graph grows too large after substitution")
    return compact(out)


def free_variables(graph: dict) -> set[str]:
    return fg_engine.variables_of(graph)


def fold(graph: dict, variables: dict | None = None, seed: int = 0):
    """Evaluate a function graph to a plain Python value (number, list, bool or str)."""
    try:
        value, kind = fg_engine.evaluate(graph, variables or {}, seed=seed, dtype=torch.float64, kind=True)
    except DiffMatError as exc:
        raise FunctionError(str(exc)) from None
    if isinstance(value, str):
        return value
    flat = value.detach().reshape(-1).tolist()
    if kind == "bool":
        return bool(flat[0] > 0.5)
    if kind == "int":
        flat = [int(round(x)) for x in flat]
    return flat[0] if len(flat) == 1 else flat


_SAFE = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$")


def sanitize_strings(graph: dict) -> dict:
    """Replace string constants that are not plain identifiers by "" (so that no free text from a
    file reaches a generated program)."""
    for node in graph["nodes"].values():
        if node["function"] == "const_string" and isinstance(node.get("data"), str):
            if node["data"] and not _SAFE.match(node["data"]):
                node["data"] = ""
    return graph
