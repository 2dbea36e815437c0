"""Writing an ``SbsGraph`` (a MaterialGraph with exposed parameters) as a Substance ``.sbs`` package.

The document follows the structure of files saved by Substance 3D Designer (see
``../shared/reference/sbs_format.md``), so that our translator reads it back into a graph that
evaluates to the same maps, and so that it looks like what an artist downloads:

- atomic nodes are ``compFilter``s named like Substance's filters, with their parameters as typed
  ``constantValue*`` elements (gradient keys as a ``gradientrgba`` paramsArray, curve points as
  ``curveluminance``), and the node seed as the ``randomseed`` base parameter;
- library nodes (generators, non-atomic filters) are ``compInstance``s of ``pkg:///NAME?dependency=UID``
  with a dependency on the stock package ``sbs://NAME.sbs`` and ``outputBridgings``;
- a parameter driven by exposed parameters is a ``dynamicValue`` function graph whose node types are
  inferred from the function names (``const_floatN``/``get_floatN``/``vectorN`` -> N components,
  others from their inputs);
- exposed parameters are ``paraminputs`` (type code, ``defaultValue``, slider ``min``/``max``);
  graph outputs carry their usages (baseColor, normal, ...) and are fed by output bridges.

Only the nodes that reach an output are written. The output is deterministic (uids come from a
generator seeded by the graph's name), so a re-export of an unchanged graph gives the same bytes.

Entry points: ``export_sbs(graph, description="") -> str`` and ``write_sbs(graph, path, ...)``.
"""
from __future__ import annotations

import random
import uuid
import zlib
from collections import defaultdict
from pathlib import Path

import numpy as np
import torch
from lxml import etree

from ..diffmat.errors import DiffMatError
from ..diffmat.functional import function_graph as fg_engine
from ..safe_files import write_atomic
from ..translator.type_codes import type_code
from ..vocabulary import OUTPUTS

FORMAT_VERSION = "1.1.0.202302"
# stock packages whose file name is not the graph's name
PACKAGE_OF = {"blur_hq_grayscale": "blur_hq", "invert_grayscale": "invert", "switch_grayscale": "blend_switch",
              "switch": "blend_switch", "multi_switch": "blend_switch", "multi_switch_grayscale": "blend_switch",
              "normal_to_height": "normal_to_height_2", "hbao": "hbao_2", "perlin_noise": "noise_perlin_noise",
              "contrast_luminosity_grayscale": "contrast_luminosity", "slope_blur_grayscale": "slope_blur",
              "histogram_scan": "histogram_scan", "safe_transform_grayscale": "safe_transform",
              "make_it_tile_patch_grayscale": "make_it_tile_patch", "vector_warp_grayscale": "vector_warp",
              "make_it_tile_photo_grayscale": "make_it_tile_photo", "tile_generator": "pattern_tile_generator",
              "tile_sampler": "pattern_tile_sampler", "shape": "pattern_shape", "clouds_2": "noise_clouds_2"}
# an array field: (parameter, cell parameter, values per key; None: all the values divided evenly)
ArrayField = tuple[str, str, int | None]
# atomic nodes whose array parameters are written as a paramsArray: (array name, its fields)
ARRAYS: dict[str, tuple[str, tuple[ArrayField, ...]]] = {
    "gradient": ("gradientrgba", (("positions", "position", 1), ("colors", "value", None))),
    "curve": ("curveluminance", (("positions", "position", 2), ("lefts", "left", 2), ("rights", "right", 2))),
}


def _num(x: float) -> str:
    """A float as Substance prints it: the float32 value, shortest text that reads back exactly."""
    f = np.float32(x)
    text = np.format_float_positional(f, unique=True, trim="-") if abs(f) >= 1e-4 or f == 0 else repr(float(f))
    return "0" if text in ("-0", "0.") else text


def _nums(values) -> str:
    return " ".join(_num(v) for v in values)


class _Uids:
    """Unique, deterministic Substance-like uids (10-digit decimals)."""

    def __init__(self, name: str):
        self.rng = random.Random(zlib.crc32(name.encode()))
        self.used: set[int] = set()

    def __call__(self) -> str:
        while True:
            u = self.rng.randrange(1_000_000_000, 1_999_999_999)
            if u not in self.used:
                self.used.add(u)
                return str(u)


def _v(parent, tag: str, value) -> etree._Element:
    el = etree.SubElement(parent, tag)
    el.set("v", str(value))
    return el


def _const(parent, kind: str, values) -> etree._Element:
    """A typed constant: kind float/int/bool/string; values a list of numbers (or a str/bool)."""
    if kind == "string":
        return _v(parent, "constantValueString", values)
    if kind == "bool":
        return _v(parent, "constantValueBool", 1 if values else 0)
    values = list(values) if isinstance(values, (list, tuple)) else [values]
    if kind == "int":
        tag = "constantValueInt32" if len(values) == 1 else f"constantValueInt{len(values)}"
        return _v(parent, tag, " ".join(str(int(v)) for v in values))
    return _v(parent, f"constantValueFloat{len(values)}", _nums(values))


def _parameter(parent, name: str, *, kind=None, value=None, dynamic=None, relative_to=None, uids=None):
    p = etree.SubElement(parent, "parameter")
    _v(p, "name", name)
    if relative_to is not None:
        _v(p, "relativeTo", relative_to)
    pv = etree.SubElement(p, "paramValue")
    if dynamic is not None:
        _dynamic(pv, dynamic, uids)
    else:
        _const(pv, kind, value)
    return p


# ---- function graphs ---------------------------------------------------------------------------
def infer_types(graph: dict) -> dict[str, tuple[str, int]]:
    """(kind, components) of every node of a function graph, from function names and inputs."""
    nodes = graph["nodes"]
    out: dict[str, tuple[str, int]] = {}
    for nid in fg_engine.reachable_order(graph):
        node = nodes[nid]
        fn, ins = node["function"], node.get("inputs") or {}
        first = next((out[ins[p]] for p in fg_engine.FUNCTIONS[fn] if p in ins), ("float", 1))
        digit = int(fn[-1]) if fn[-1].isdigit() else 1
        if fn.startswith(("const_float", "get_float", "vector", "tofloat")):
            t = ("float", digit)
        elif fn.startswith(("const_int", "get_integer", "ivector", "toint", "iswizzle")):
            t = ("int", digit)
        elif fn in ("const_bool", "get_bool", "and", "or", "not", "eq", "noteq", "gt", "gteq", "lr", "lreq"):
            t = ("bool", 1)
        elif fn in ("const_string", "get_string"):
            t = ("string", 1)
        elif fn.startswith("swizzle"):
            t = (first[0], digit)
        elif fn in ("dot", "length", "samplelum"):
            t = ("float", 1)
        elif fn == "samplecol":
            t = ("float", 4)
        elif fn == "cross":
            t = ("float", 3)
        elif fn == "cartesian":
            t = ("float", 2)
        elif fn == "ifelse":
            t = _input_type(out, ins, "ifpath", first)
        elif fn == "sequence":
            t = _input_type(out, ins, "seqlast", first)
        elif fn in ("add", "sub", "mul", "div", "min", "max", "mod", "pow", "atan2"):
            a, b = _input_type(out, ins, "a", first), _input_type(out, ins, "b", first)
            t = a if a[1] >= b[1] else b
        else:
            t = first
        out[nid] = t
    return out


def _input_type(types: dict[str, tuple[str, int]], inputs: dict[str, str], port: str,
                default: tuple[str, int]) -> tuple[str, int]:
    """The type of the node wired to ``port``, ``default`` when the port is not wired."""
    ref = inputs.get(port)
    return default if ref is None else types.get(ref, default)


def _dynamic(parent, graph: dict, uids) -> None:
    fg_engine.validate(graph)
    types = infer_types(graph)
    order = fg_engine.reachable_order(graph)
    ids = {nid: uids() for nid in order}
    dyn = etree.SubElement(parent, "dynamicValue")
    _v(dyn, "rootnode", ids[graph["root"]])
    pnodes = etree.SubElement(dyn, "paramNodes")
    for i, nid in enumerate(order):
        node = graph["nodes"][nid]
        fn = node["function"]
        kind, n = types[nid]
        pn = etree.SubElement(pnodes, "paramNode")
        _v(pn, "uid", ids[nid])
        _v(pn, "function", fn)
        _v(pn, "type", type_code(kind, n))
        ins = node.get("inputs") or {}
        if ins:
            conns = etree.SubElement(pn, "connections")
            for port in fg_engine.FUNCTIONS[fn]:
                if port in ins:
                    c = etree.SubElement(conns, "connection")
                    _v(c, "identifier", port)
                    _v(c, "connRef", ids[ins[port]])
        data = node.get("data")
        if data is not None:
            datas = etree.SubElement(pn, "funcDatas")
            if fn in ("samplelum", "samplecol"):
                for key in ("input", "filtering"):
                    if key in data:
                        fd = etree.SubElement(datas, "funcData")
                        _v(fd, "name", key)
                        _v(etree.SubElement(fd, "constantValue"), "constantValueInt1", int(data[key]))
            else:
                fd = etree.SubElement(datas, "funcData")
                _v(fd, "name", fn)
                cv = etree.SubElement(fd, "constantValue")
                if fn.startswith(("get_", "const_string")) or fn == "set":
                    _v(cv, "constantValueString", data)
                elif fn == "const_bool":
                    _v(cv, "constantValueBool", 1 if data else 0)
                elif fn.startswith(("swizzle", "iswizzle", "const_int")):
                    vals = data if isinstance(data, list) else [data]
                    tag = "constantValueInt1" if len(vals) == 1 else f"constantValueInt{len(vals)}"
                    _v(cv, tag, " ".join(str(int(x)) for x in vals))
                else:
                    _const(cv, "float", data)
        gl = etree.SubElement(pn, "GUILayout")
        _v(gl, "gpos", f"{-160 * (len(order) - 1 - i)} 0 0")


# ---- the graph ---------------------------------------------------------------------------------
def probe_channels(graph, size: int = 32) -> dict[tuple[str, str], int]:
    """Channel count (1 or 4) of every node output that reaches a material output."""
    seen: dict[tuple[str, str], int] = {}
    hooks = []
    for name, node in graph.nodes.items():
        def hook(mod, args, kwargs, result, _n=name):
            results = result if isinstance(result, tuple) else (result,)
            for o, r in zip(mod.spec.outputs, results):
                seen[(_n, o)] = int(r.shape[1])
        hooks.append(node.register_forward_hook(hook, with_kwargs=True))
    try:
        graph.clear_cache()
        with torch.no_grad():
            graph(size=size, seed=0, cache=False)
    finally:
        for h in hooks:
            h.remove()
        graph.clear_cache()
    return seen


def stable_order(graph) -> list[str]:
    """The nodes that reach an output, sources first, deterministic: a depth-first walk from the
    outputs (in usage order) through inputs in slot order (``MaterialGraph.order`` ties follow
    set iteration, which changes between processes)."""
    out: list[str] = []
    state: dict[str, int] = {}
    for usage in graph.outputs:
        stack = [(graph.outputs[usage][0], False)]
        while stack:
            n, done = stack.pop()
            if done:
                if state[n] == 1:
                    state[n] = 2
                    out.append(n)
                continue
            if state.get(n):
                if state[n] == 1:
                    raise DiffMatError(f"graph {graph.name}: cycle through node {n!r}")
                continue
            state[n] = 1
            stack.append((n, True))
            for ref in reversed([r for r in graph.links[n] if r is not None]):
                if not state.get(ref[0]):
                    stack.append((ref[0], False))
    return out


def _depths(graph, order) -> dict[str, int]:
    depth: dict[str, int] = {}
    for n in order:
        depth[n] = 1 + max((depth[s] for s, _ in filter(None, graph.links[n])), default=-1)
    return depth


def _close(a, b) -> bool:
    a = list(a) if isinstance(a, (list, tuple)) else [a]
    b = list(b) if isinstance(b, (list, tuple)) else [b]
    return len(a) == len(b) and all(np.float32(x) == np.float32(y) for x, y in zip(a, b))


def export_sbs(graph, description: str = "", *, author: str = "blender_match") -> str:
    """The ``.sbs`` document (XML text) of ``graph`` (an SbsGraph or a MaterialGraph)."""
    name = graph.name
    uids = _Uids(name)
    graph.order()  # checks for cycles
    order = stable_order(graph)
    channels = probe_channels(graph)

    pkg = _package(name, description)
    deps_el = etree.SubElement(pkg, "dependencies")
    g = _graph_element(etree.SubElement(pkg, "content"), name, description, author, uids)
    _paraminputs(g, getattr(graph, "exposed", None), uids)
    out_uid = _graph_outputs(g, graph, channels, uids)
    dep_uid = _comp_nodes(g, graph, order, channels, out_uid, uids)
    _graph_footer(g, graph, out_uid)
    _dependencies(deps_el, dep_uid)
    text = etree.tostring(pkg, pretty_print=True, xml_declaration=True, encoding="UTF-8")
    return text.decode("utf-8")


def _package(name: str, description: str) -> etree._Element:
    """The ``package`` root with its identification fields (the file uid derives from the name)."""
    pkg = etree.Element("package")
    _v(pkg, "identifier", name)
    if description:
        _v(pkg, "desc", description)
    _v(pkg, "formatVersion", FORMAT_VERSION)
    _v(pkg, "updaterVersion", FORMAT_VERSION)
    _v(pkg, "fileUID", "{" + str(uuid.uuid5(uuid.NAMESPACE_URL, f"blender_match/library/{name}")) + "}")
    _v(pkg, "versionUID", "0")
    return pkg


def _graph_element(content, name: str, description: str, author: str, uids) -> etree._Element:
    g = etree.SubElement(content, "graph")
    _v(g, "identifier", name)
    _v(g, "uid", uids())
    attrs = etree.SubElement(g, "attributes")
    _v(attrs, "category", "blender_match/library")
    _v(attrs, "label", name.replace("_", " ").title())
    _v(attrs, "author", author)
    if description:
        _v(attrs, "description", description)
    _v(g, "graphtype", "material")
    return g


def _paraminputs(g, exposed, uids) -> None:
    """The exposed parameters (none for a plain MaterialGraph) as ``paraminput``s."""
    pis = etree.SubElement(g, "paraminputs")
    if exposed is None:
        return
    values = exposed.values()
    for pname, kind in exposed.kinds.items():
        pi = etree.SubElement(pis, "paraminput")
        _v(pi, "identifier", pname)
        _v(pi, "uid", uids())
        a = etree.SubElement(pi, "attributes")
        _v(a, "label", pname.replace("_", " ").title())
        if kind == "float":
            _float_paraminput(pi, values[pname], exposed.ranges[pname])
        else:
            _v(pi, "type", type_code(kind, 1))
            _const(etree.SubElement(pi, "defaultValue"), kind, values[pname])
            widget = etree.SubElement(pi, "defaultWidget")
            _v(widget, "name", {"int": "slider", "bool": "buttons", "string": "text"}[kind])
        _v(pi, "group", "Parameters")


def _float_paraminput(pi, value, value_range: tuple[float, float]) -> None:
    """Type, default and widget of a float exposed parameter: a colour picker for 3/4 components
    in [0, 1], a slider with the range otherwise."""
    val = [float(x) for x in torch.as_tensor(value).detach().reshape(-1)]
    lo, hi = value_range
    _v(pi, "type", type_code("float", len(val)))
    _const(etree.SubElement(pi, "defaultValue"), "float", val)
    widget = etree.SubElement(pi, "defaultWidget")
    is_color = len(val) in (3, 4) and (lo, hi) == (0.0, 1.0)
    _v(widget, "name", "color" if is_color else "slider")
    opts = etree.SubElement(widget, "options")
    for oname, oval in (("min", _num(lo)), ("max", _num(hi)), ("step", "0.01"), ("clamp", "1")):
        o = etree.SubElement(opts, "option")
        _v(o, "name", oname)
        _v(o, "value", oval)


def _graph_outputs(g, graph, channels: dict[tuple[str, str], int], uids) -> dict[str, str]:
    """The ``graphoutput``s with their usages; returns the uid of each usage's output."""
    gouts = etree.SubElement(g, "graphOutputs")
    out_uid: dict[str, str] = {}
    for usage, (src, o) in graph.outputs.items():
        go = etree.SubElement(gouts, "graphoutput")
        _v(go, "identifier", usage)
        out_uid[usage] = uids()
        _v(go, "uid", out_uid[usage])
        a = etree.SubElement(go, "attributes")
        _v(a, "label", OUTPUTS[usage].label)
        us = etree.SubElement(etree.SubElement(go, "usages"), "usage")
        gray = channels.get((src, o), 4) == 1
        _v(us, "components", "L" if gray else "RGBA")
        _v(us, "name", OUTPUTS[usage].sbs_usage)
        if gray:
            _v(go, "channels", 2)
        _v(go, "group", "Material")
    return out_uid


def _comp_nodes(g, graph, order: list[str], channels: dict[tuple[str, str], int], out_uid: dict[str, str],
                uids) -> dict[str, str]:
    """The ``compNodes``: the graph's nodes laid out in columns by depth, then one output bridge per
    usage in a last column. Returns the uid of each stock package the nodes instantiate."""
    comp = etree.SubElement(g, "compNodes")
    node_uid = {n: uids() for n in order}
    output_uid = {(n, o): uids() for n in order for o in graph.nodes[n].spec.outputs}
    depth = _depths(graph, order)
    rows: dict[int, int] = defaultdict(int)
    dep_uid: dict[str, str] = {}
    bindings = getattr(graph, "bindings", {})
    for n in order:
        cn = etree.SubElement(comp, "compNode")
        _v(cn, "uid", node_uid[n])
        _v(cn, "GUIName", n)
        gl = etree.SubElement(cn, "GUILayout")
        _v(gl, "gpos", f"{160 * depth[n]} {160 * rows[depth[n]]} 0")
        rows[depth[n]] += 1
        _comp_outputs(cn, graph.nodes[n].spec, n, channels, output_uid)
        _connections(cn, graph, n, node_uid, output_uid)
        _implementation(cn, graph.nodes[n], n, bindings.get(n, {}), output_uid, dep_uid, uids)
    last = 1 + max(depth.values(), default=0)
    for i, (usage, (src, o)) in enumerate(graph.outputs.items()):
        cn = etree.SubElement(comp, "compNode")
        _v(cn, "uid", uids())
        gl = etree.SubElement(cn, "GUILayout")
        _v(gl, "gpos", f"{160 * last} {160 * i} 0")
        c = etree.SubElement(etree.SubElement(cn, "connections"), "connection")
        _v(c, "identifier", "inputNodeOutput")
        _v(c, "connRef", node_uid[src])
        _v(c, "connRefOutput", output_uid[(src, o)])
        ob = etree.SubElement(etree.SubElement(cn, "compImplementation"), "compOutputBridge")
        _v(ob, "output", out_uid[usage])
    return dep_uid


def _comp_outputs(cn, spec, n: str, channels: dict[tuple[str, str], int],
                  output_uid: dict[tuple[str, str], str]) -> None:
    outs = etree.SubElement(cn, "compOutputs")
    for o in spec.outputs:
        co = etree.SubElement(outs, "compOutput")
        _v(co, "uid", output_uid[(n, o)])
        _v(co, "comptype", 2 if channels.get((n, o), 4) == 1 else 1)


def _connections(cn, graph, n: str, node_uid: dict[str, str], output_uid: dict[tuple[str, str], str]) -> None:
    links = [(slot.name, ref) for slot, ref in zip(graph.nodes[n].spec.inputs, graph.links[n]) if ref is not None]
    if not links:
        return
    conns = etree.SubElement(cn, "connections")
    for slot, (src, o) in links:
        c = etree.SubElement(conns, "connection")
        _v(c, "identifier", slot)
        _v(c, "connRef", node_uid[src])
        _v(c, "connRefOutput", output_uid[(src, o)])


def _implementation(cn, node, n: str, bound: dict, output_uid: dict[tuple[str, str], str],
                    dep_uid: dict[str, str], uids) -> None:
    """An atomic node as a ``compFilter``; any other as a ``compInstance`` of its stock package
    (registered in ``dep_uid`` on first use) with output bridgings."""
    spec = node.spec
    impl = etree.SubElement(cn, "compImplementation")
    if spec.kind == "atomic":
        el = etree.SubElement(impl, "compFilter")
        _v(el, "filter", spec.name)
    else:
        el = etree.SubElement(impl, "compInstance")
        pkg_name = PACKAGE_OF.get(spec.name, spec.name)
        if pkg_name not in dep_uid:
            dep_uid[pkg_name] = uids()
        _v(el, "path", f"pkg:///{spec.name}?dependency={dep_uid[pkg_name]}")
    params = etree.SubElement(el, "parameters")
    _node_params(params, node, bound, uids)
    if node.seed:
        _parameter(params, "randomseed", kind="int", value=[node.seed], relative_to=1)
    if spec.name in ARRAYS and spec.kind == "atomic":
        _arrays(el, node, uids)
    if spec.kind != "atomic":
        br = etree.SubElement(el, "outputBridgings")
        for o in spec.outputs:
            b = etree.SubElement(br, "outputBridging")
            _v(b, "uid", output_uid[(n, o)])
            _v(b, "identifier", o)


def _graph_footer(g, graph, out_uid: dict[str, str]) -> None:
    """Base parameters, options and root outputs of the graph."""
    base = etree.SubElement(g, "baseParameters")
    _parameter(base, "outputsize", kind="int", value=[0, 0], relative_to=1)
    _parameter(base, "format", kind="int", value=[0], relative_to=1)
    opts = etree.SubElement(g, "options")
    for oname, oval in (("defaultParentSize", "11x11"), ("export/fromGraph/autoExport", "false")):
        o = etree.SubElement(opts, "option")
        _v(o, "name", oname)
        _v(o, "value", oval)
    root = etree.SubElement(etree.SubElement(g, "root"), "rootOutputs")
    for usage in graph.outputs:
        ro = etree.SubElement(root, "rootOutput")
        _v(ro, "output", out_uid[usage])
        _v(ro, "format", 0)
        _v(ro, "usertag", "")


def _dependencies(deps_el, dep_uid: dict[str, str]) -> None:
    for pkg_name, u in sorted(dep_uid.items()):
        d = etree.SubElement(deps_el, "dependency")
        _v(d, "filename", f"sbs://{pkg_name}.sbs")
        _v(d, "uid", u)
        _v(d, "type", "package")
        _v(d, "fileUID", "0")
        _v(d, "versionUID", "0")


def _node_params(parent, node, bound: dict, uids):
    spec = node.spec
    values = node.values()
    arrays = {f for f, _, _ in ARRAYS[spec.name][1]} if spec.kind == "atomic" and spec.name in ARRAYS else set()
    for p in spec.params:
        if p.name in bound:
            _parameter(parent, p.name, dynamic=bound[p.name], uids=uids)
            continue
        if p.name in arrays:
            continue
        if p.continuous:
            val = [float(x) for x in values[p.name].detach().reshape(-1)]
            if _close(val, p.default):
                continue
            _parameter(parent, p.name, kind="float", value=val)
            continue
        val = node.fixed[p.name]
        if p.kind == "string":
            if p.name in ("perpixel", "function") and val:
                _parameter(parent, p.name, dynamic=fg_engine.loads(val), uids=uids)
            elif val != p.default:
                _parameter(parent, p.name, kind="string", value=val)
            continue
        if val == p.default and p.name != "colorswitch":
            continue
        _parameter(parent, p.name, kind="bool" if p.kind == "bool" else "int", value=val if p.kind == "bool" else [val])


def _arrays(el, node, uids):
    name, fields = ARRAYS[node.spec.name]
    values = node.values()
    data = {f: [float(x) for x in values[f].detach().reshape(-1)] for f, _, _ in fields}
    positions, _, position_width = fields[0]
    assert position_width is not None  # the positions field always has a fixed width
    keys = len(data[positions]) // position_width
    arrs = etree.SubElement(el, "paramsArrays")
    arr = etree.SubElement(arrs, "paramsArray")
    _v(arr, "name", name)
    _v(arr, "uid", uids())
    cells = etree.SubElement(arr, "paramsArrayCells")
    for k in range(keys):
        cell = etree.SubElement(cells, "paramsArrayCell")
        _v(cell, "uid", uids())
        ps = etree.SubElement(cell, "parameters")
        for f, xml, width in fields:
            width = width or len(data[f]) // keys
            _parameter(ps, xml, kind="float", value=data[f][k * width:(k + 1) * width])
        if name == "gradientrgba":
            _parameter(ps, "midpoint", kind="float", value=[0.5])
        else:
            for flag in ("isLeftBroken", "isRightBroken", "isLocked"):
                _parameter(ps, flag, kind="bool", value=flag == "isLocked")


def write_sbs(graph, path: Path, description: str = "", overwrite: bool = True) -> Path:
    """Write ``graph`` as an ``.sbs`` file at ``path`` (atomically)."""
    path = Path(path)
    write_atomic(path, export_sbs(graph, description).encode("utf-8"), overwrite=overwrite)
    return path


__all__ = ["export_sbs", "write_sbs", "infer_types", "probe_channels", "DiffMatError"]
