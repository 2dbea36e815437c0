"""From the (safely parsed) XML of a .sbs package to the model of model.py.

Accepts both spellings the format has used: values in ``v`` attributes or ``<value v>`` children,
``connections/connection`` or ``connexions/connexion``. Structural problems (a node without uid,
a duplicate uid, a connection without its source) are TranslatorErrors; a parameter that cannot be
decoded is kept with its ``error`` so the builder can fall back to the default and report it.
"""
from __future__ import annotations

from .errors import TranslatorError
from .function_graphs import FunctionError, parse_dynamic
from .model import Connection, Graph, GraphOutput, Node, Package, Param, ParamInput
from .values import BadValue, child_v, decode_container, to_float, to_int
from .xml_safety import read_document

MAX_GRAPHS = 1000
MAX_NODES_PER_GRAPH = 20000


def load_package(path, root=None) -> Package:
    """Parse the .sbs file at ``path`` (or the already parsed ``root`` element)."""
    root = read_document(path) if root is None else root
    pkg = Package(path=str(path))
    for dep in root.findall("dependencies/dependency"):
        uid, filename = child_v(dep, "uid"), child_v(dep, "filename")
        if uid is not None and filename is not None:
            pkg.dependencies[uid.strip()] = filename
    content = root.find("content")
    if content is not None:
        _walk(pkg, content, [], path)
    return pkg


def _walk(pkg: Package, content, folders: list[str], path):
    for el in content:
        if el.tag == "group":
            name = child_v(el, "identifier") or ""
            sub = el.find("content")
            if sub is not None:
                if len(folders) > 32:
                    raise TranslatorError(path, "groups nested too deeply")
                _walk(pkg, sub, folders + [name], path)
        elif el.tag == "graph":
            if len(pkg.graphs) >= MAX_GRAPHS:
                raise TranslatorError(path, f"more than {MAX_GRAPHS} graphs")
            pkg.graphs.append(_graph(el, folders, path, pkg.warnings))


def _param(el, warnings: list[str], where: str) -> Param | None:
    name = child_v(el, "name")
    if not name:
        return None
    p = Param(name=name)
    rel = child_v(el, "relativeTo")
    if rel is not None:
        try:
            p.relative_to = to_int(rel)
        except BadValue:
            p.relative_to = None
    pv = el.find("paramValue")
    if pv is None:
        p.error = "no value"
        return p
    dyn = pv.find("dynamicValue")
    try:
        if dyn is not None:
            p.dynamic = parse_dynamic(dyn)
        else:
            p.constant = decode_container(pv)
    except (BadValue, FunctionError) as exc:
        p.error = str(exc)
    return p


def _params(container, warnings, where) -> dict[str, Param]:
    out: dict[str, Param] = {}
    if container is None:
        return out
    for el in container.findall("parameter"):
        p = _param(el, warnings, where)
        if p is not None:
            out[p.name.lower()] = p
    return out


def _connections(el) -> list[Connection]:
    out = []
    for c in el.findall("connections/connection") + el.findall("connexions/connexion"):
        ident, src = child_v(c, "identifier"), child_v(c, "connRef")
        if ident is None or src is None:
            continue
        out.append(Connection(ident, src.strip(), (child_v(c, "connRefOutput") or "").strip() or None))
    return out


def _outputs(el) -> list[tuple[str, int | None]]:
    """A node's outputs: (uid, comptype or None)."""
    outputs: list[tuple[str, int | None]] = []
    for out in el.findall("compOutputs/compOutput"):
        ouid = child_v(out, "uid")
        if ouid is None:
            continue
        text = child_v(out, "comptype")
        try:
            ct = to_int(text) if text is not None else None
        except BadValue:
            ct = None
        outputs.append((ouid.strip(), ct))
    return outputs


def _param_arrays(impl, warnings, uid: str) -> dict[str, list[dict]]:
    """A filter's parameter arrays (gradient keys, curve points): name -> cells of constants."""
    arrays = {}
    for arr in impl.findall("paramsArrays/paramsArray"):
        name = (child_v(arr, "name") or "").lower()
        cells = []
        for cell in arr.findall("paramsArrayCells/paramsArrayCell"):
            values = {}
            for pname, p in _params(cell.find("parameters"), warnings, uid).items():
                if p.constant is not None:
                    values[pname] = p.constant
            cells.append(values)
        if name:
            arrays[name] = cells
    return arrays


def _node(el, path, warnings) -> Node:
    uid = child_v(el, "uid")
    if uid is None or not uid.strip():
        raise TranslatorError(path, "a node has no uid")
    uid = uid.strip()
    impl_el = el.find("compImplementation")
    impl = next((c for c in impl_el if isinstance(c.tag, str)), None) if impl_el is not None else None
    node = Node(uid=uid, impl="unknown")
    node.connections = _connections(el)
    node.outputs = _outputs(el)
    if impl is None:
        return node
    if impl.tag == "compFilter":
        node.impl, node.name = "filter", (child_v(impl, "filter") or "")
        node.params = _params(impl.find("parameters"), warnings, uid)
        node.arrays = _param_arrays(impl, warnings, uid)
    elif impl.tag == "compInstance":
        node.impl, node.name = "instance", (child_v(impl, "path") or "")
        node.params = _params(impl.find("parameters"), warnings, uid)
        for b in impl.findall("outputBridgings/outputBridging"):
            buid, ident = child_v(b, "uid"), child_v(b, "identifier")
            if buid is not None and ident is not None:
                node.bridgings[buid.strip()] = ident
    elif impl.tag == "compInputBridge":
        node.impl, node.ref = "input", (child_v(impl, "entry") or "").strip()
        node.params = _params(impl.find("parameters"), warnings, uid)
    elif impl.tag == "compOutputBridge":
        node.impl, node.ref = "output", (child_v(impl, "output") or "").strip()
    else:
        node.name = impl.tag
    return node


def _paraminput(el) -> ParamInput | None:
    ident, uid = child_v(el, "identifier"), child_v(el, "uid")
    if not ident or uid is None:
        return None
    try:
        typ = to_int(child_v(el, "type")) if child_v(el, "type") is not None else None
    except BadValue:
        typ = None
    pi = ParamInput(identifier=ident, uid=uid.strip(), type=typ)
    try:
        pi.default = decode_container(el.find("defaultValue"))
    except BadValue:
        pi.default = None
    for opt in el.findall("defaultWidget/options/option"):
        name, value = child_v(opt, "name"), child_v(opt, "value")
        if name in ("min", "max") and value is not None:
            try:
                setattr(pi, name, to_float(value.split(";")[0]))
            except BadValue:
                pass
    return pi


def _graph(el, folders: list[str], path, warnings) -> Graph:
    ident = child_v(el, "identifier") or ""
    g = Graph(identifier=ident, uid=(child_v(el, "uid") or "").strip(), path="/".join(folders + [ident]))
    for pi in el.findall("paraminputs/paraminput"):
        p = _paraminput(pi)
        if p is not None:
            g.paraminputs.append(p)
    for go in el.findall("graphOutputs/graphoutput"):
        gid, guid = child_v(go, "identifier"), child_v(go, "uid")
        if guid is None:
            continue
        usages = [child_v(u, "name") or "" for u in go.findall("usages/usage")]
        g.outputs.append(GraphOutput(identifier=gid or "", uid=guid.strip(), usages=[u for u in usages if u]))
    g.base_params = _params(el.find("baseParameters"), warnings, ident)
    for opt in el.findall("options/option"):
        name, value = child_v(opt, "name"), child_v(opt, "value")
        if name and value is not None:
            g.options[name] = value
    comp = el.findall("compNodes/compNode")
    if len(comp) > MAX_NODES_PER_GRAPH:
        raise TranslatorError(path, f"graph {ident[:60]!r} has more than {MAX_NODES_PER_GRAPH} nodes")
    for cn in comp:
        node = _node(cn, path, warnings)
        if node.uid in g.nodes:
            raise TranslatorError(path, f"graph {ident[:60]!r}: duplicate node uid {node.uid[:30]}")
        g.nodes[node.uid] = node
    return g
