"""Program generation (the MATch paper, section 5.7 step 4): a readable Python module that
rebuilds the translated graph with DiffMat calls (``graph.add(...)`` in topological order).

Safety: the program carries no text from the .sbs file except validated identifiers (node names,
exposed parameter names, registered node/parameter/slot names) and literals produced by
``repr()`` of numbers, booleans and validated strings; every string is checked again here, and a
string that fails is an internal error rather than a line of the program.
"""
from __future__ import annotations

import json
import math
import re

from ..diffmat.functional import function_graph as fg_engine
from ..diffmat.nodes import has_spec
from ..errors import BlenderMatchError
from .ir import IRGraph

_SAFE = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$")
_REF = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*:[a-z0-9_][a-z0-9_\-]*$")  # node:output (registered output name)
_ID = re.compile(r"^[0-9]{1,9}$")
_SPEC = re.compile(r"^[a-z0-9_][a-z0-9_\-]*$")


class CodegenError(BlenderMatchError):
    """The IR holds something that must not reach a program (a bug, not a bad file)."""


def _safe_str(s: str) -> str:
    if _SAFE.match(s) or _REF.match(s) or _ID.match(s) or s in fg_engine.SYSTEM_VARIABLES or s == "":
        return s
    if _SPEC.match(s):
        return _spec_name(s)
    try:  # a function graph's JSON text produced by the translator
        _check_strings(json.loads(s))
        return s
    except (ValueError, CodegenError):
        pass
    raise CodegenError(f"refusing to emit string {s[:40]!r}")


def _check_strings(value):
    if isinstance(value, str):
        if not (_SAFE.match(value) or _ID.match(value) or value in fg_engine.SYSTEM_VARIABLES or value == ""):
            raise CodegenError(f"refusing to emit string {value[:40]!r}")
    elif isinstance(value, dict):
        for k, v in value.items():
            _check_strings(k)
            _check_strings(v)
    elif isinstance(value, (list, tuple)):
        for v in value:
            _check_strings(v)


def lit(value) -> str:
    """A Python literal for ``value`` (None, bool, int, float, validated str, list, dict)."""
    if value is None or isinstance(value, bool):
        return repr(value)
    if isinstance(value, int):
        return repr(int(value))
    if isinstance(value, float):
        if not math.isfinite(value):
            raise CodegenError("non-finite number")
        return repr(float(value))
    if isinstance(value, str):
        return repr(_safe_str(value))
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(lit(v) for v in value) + "]"
    if isinstance(value, dict):
        return "{" + ", ".join(f"{lit(k)}: {lit(v)}" for k, v in value.items()) + "}"
    raise CodegenError(f"cannot emit a {type(value).__name__}")


def _spec_name(name: str) -> str:
    if not (_SPEC.match(name) and has_spec(name)):
        raise CodegenError(f"not a registered node: {name[:40]!r}")
    return name


def _ident(name: str) -> str:
    if not _SAFE.match(name):
        raise CodegenError(f"not an identifier: {name[:40]!r}")
    return name


def generate(ir: IRGraph, order: list[str], source_name: str = "graph") -> str:
    """The program text for ``ir`` (nodes in ``order``)."""
    src = _ident(re.sub(r"[^A-Za-z0-9_]", "_", source_name) or "graph") if source_name else "graph"
    lines = [
        f'"""DiffMat program for graph {_ident(ir.name)} (translated from {src} by blender-match translate).',
        "",
        f"Parameter mode {_ident(ir.mode)}. build() returns the graph (an SbsGraph, i.e. a MaterialGraph);",
        "evaluate it with build()(size=256). Run as a script to print the output shapes.",
        '"""',
        "from blender_match.diffmat.nodes import Node",
        "from blender_match.translator.runtime import SbsGraph",
        "",
        f"GRAPH_NAME = {lit(ir.name)}",
        f"MODE = {lit(ir.mode)}",
        "",
        "",
        "def build():",
        "    graph = SbsGraph(GRAPH_NAME)",
    ]
    if ir.exposed:
        lines.append("    # exposed parameters (graph-level)")
    for e in ir.exposed:
        lines.append(f"    graph.expose({lit(_ident(e.name))}, {lit(e.default)}, kind={lit(e.kind)}, "
                     f"min={lit(float(e.min))}, max={lit(float(e.max))})")
    for name in order:
        node = ir.nodes[name]
        w, h = node.size_log2
        note = f"{_ident(node.status)}"
        if node.origin and node.origin != node.spec:
            note += f" for {_ident(node.origin)}" if _SAFE.match(node.origin) else ""
        lines.append(f"    # {_ident(name)}: {note}; output size 2^{int(w)} x 2^{int(h)}, format {int(node.format)}")
        params = lit(dict(node.params)) if node.params else "{}"
        inputs = {slot: f"{r.node}:{r.output}" for slot, r in node.inputs.items()}
        seed = f", seed={int(node.seed)}" if node.seed else ""
        spec = repr(_spec_name(node.spec))
        call = f"    graph.add({lit(_ident(name))}, Node({spec}, {params}{seed}, widen_ranges=True)"
        call += f", {lit(inputs)})" if inputs else ")"
        lines.append(call)
        for p, graph in node.bindings.items():
            lines.append(f"    graph.bind({lit(name)}, {lit(_ident(p))}, {lit(graph)})")
    for usage, r in ir.outputs.items():
        lines.append(f"    graph.set_output({lit(_ident(usage))}, {lit(f'{r.node}:{r.output}')})")
    lines += [
        "    graph.set_mode(MODE)",
        "    return graph",
        "",
        "",
        'if __name__ == "__main__":',
        "    import sys",
        "",
        "    size = int(sys.argv[1]) if len(sys.argv) > 1 else 256",
        "    maps = build()(size=size)",
        "    for usage, image in maps.items():",
        "        print(usage, tuple(image.shape))",
        "",
    ]
    text = "\n".join(lines)
    compile(text, "<generated>", "exec")
    return text
