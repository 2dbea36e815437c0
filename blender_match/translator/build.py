"""Graph replication and node-parameter conversion (the MATch paper, section 5.7 steps 1-2): from
the parsed package (model.py) to the IR (ir.py).

- Each compFilter maps to the registered node of the same (lower-case) name; each compInstance of
  a library graph (``sbs://``) to the registered node named like the graph, trying a few spellings
  (``clouds_2`` / ``noise_clouds_2``, ...); instances of graphs of the same package (``?himself``)
  or of a local dependency file are inlined recursively. Anything else becomes a pass-through of
  its first connected input (converted to the channel count the file records) or a uniform gray.
- Inputs, outputs and parameters are matched by lower-case identifier (``input:1`` becomes
  ``input_1``); an instance output whose identifier is not the spec's (``Clouds_2`` vs ``output``)
  falls back to the spec's single (or same-position) output.
- Parameters absent from the file keep the spec's default. Constants are fitted to the parameter
  (a Float4 level on a scalar parameter keeps its first component; a Float3 colour gets the
  default's alpha). Function graphs are composed with the values of the graph's variables:
  exposed parameters (runtime getters, or their defaults in mode "all"), an inlined sub-graph's
  parameters (the instance's values), value pins (``#name``, fed by value processors), system
  variables (``$size``, ``$sizelog2``, ``$normalformat`` = 0 (DirectX), ``$time`` = 0). A graph that
  becomes a binding (outside mode "all"), so the parameter is not optimised; a constant one is
  folded into the value as well, so the graph evaluates the same without the binding.
- Value outputs (value processors, value input bridges) do not travel as images: they are function
  graphs substituted into the consumers that read them.
- Base parameters: ``randomseed`` becomes the node's seed (added to the inlining instance's seed);
  ``outputsize`` and ``format`` are resolved through inheritance (absolute / relative to parent /
  relative to primary input; missing = input when connected, else parent) and recorded per node;
  the MaterialGraph itself evaluates every node at the one resolution it is asked for.
"""
from __future__ import annotations

import math
import os
import re
from collections import Counter

from ..diffmat.functional import function_graph as fg_engine
from ..diffmat.nodes import get_spec, has_spec
from ..vocabulary import MATERIAL_OUTPUTS
from . import aliases
from . import function_graphs as fgs
from .dataflow import toposort
from .errors import TranslatorError
from .ir import Exposed, IRGraph, IRNode, Ref
from .model import Graph, Node, Package, Param
from .parse import load_package
from .runtime import fit_components
from .type_codes import TYPE_CODES
from .values import IMAGE_TYPES, BadValue, ClampedValue, Value
from .xml_safety import MAX_BYTES, read_document

SAFE = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$")
MAX_DEPTH = 16
MAX_IR_NODES = 20000
MAX_WARNINGS = 200
BASE_PARAMS = {"outputsize", "format", "pixelsize", "pixelratio", "tiling", "quality", "randomseed"}
# the material outputs a graph may name, and the channel count the engine produces for each
USAGES = {output.name: output.channels for output in MATERIAL_OUTPUTS}
PRIMARY_SLOTS = ("destination", "input1", "input", "input_1", "source", "background", "mask", "input_2")
UNCONNECTED = (0.0, 0.0, 0.0, 0.0)
# nodes whose "any" inputs need not have the output's channel count
NOT_VARIANT = {"pixelprocessor", "fxmaps", "shuffle", "passthrough"}
GRAY = (0.5, 0.5, 0.5, 1.0)
FLAT_NORMAL = (0.5, 0.5, 1.0, 1.0)  # a tangent-space normal map's "straight up"


def stand_in_colour(name: str) -> tuple[float, ...]:
    """The colour of the uniform that stands in for an unsupported node with nothing to pass
    through: a flat normal for a node whose name says it makes normals (Substance's
    ``scratches_generator_normal``, say), since a grey there is a normal lying in the surface
    (z = 0) that renders a metal black and tilts every normal it is combined with; grey otherwise."""
    return FLAT_NORMAL if "normal" in name.lower().replace("-", "_").split("_") else GRAY


def safe_name(text: str, fallback: str = "node") -> str:
    """``text`` made a lower-case identifier (used for names derived from registered names)."""
    s = re.sub(r"[^A-Za-z0-9_]", "_", str(text))[:48].lower().strip("_")
    if not s or not SAFE.match(s):
        s = f"{fallback}_{s}" if s else fallback
    return s if SAFE.match(s) else fallback


def xml_name(text: str, fallback: str) -> str:
    """A name taken from the file: kept (lower case) only when it is already a short identifier."""
    return text.lower() if isinstance(text, str) and len(text) <= 64 and SAFE.match(text) else fallback


def report_name(text: str) -> str:
    """A name from the file for the JSON report (never for the program)."""
    return re.sub(r"[^A-Za-z0-9_\-]", "_", str(text))[:64].lower() or "unnamed"


def channels_of(comptype) -> int | None:
    return {1: 4, 2: 1}.get(comptype)


def _library_candidates(name: str, filename: str | None) -> list[str]:
    """Registered-name spellings to try for library graph ``name`` (old and new library names)."""
    low = name.lower()
    out = [low]
    for prefix in ("noise_", "pattern_"):
        out.append(low[len(prefix):] if low.startswith(prefix) else prefix + low)
    stem = re.sub(r"\.(sbs|sbsar)$", "", os.path.basename(filename or "")).lower()
    if stem and low == re.sub(r"^(noise_|pattern_)", "", stem):
        out.append(stem)
    if re.search(r"_\d+$", low):  # perlin_noise_1 -> perlin_noise
        out.append(re.sub(r"_\d+$", "", low))
    # spellings across library versions: directionnal/directional, _v2 / _legacy suffixes,
    # spaces or dashes in the name
    for variant in (low.replace("directionnal", "directional"), low.replace("directional_", "directionnal_"),
                    re.sub(r"_(v\d+|legacy)$", "", low), re.sub(r"[^a-z0-9]+", "_", low).strip("_")):
        out.append(variant)
    return list(dict.fromkeys(out))


def _variant_candidates(name: str) -> list[str]:
    """Approximate stand-ins tried after every exact spelling: the colour / grayscale twin of a
    filter (``blur_hq_color`` -> ``blur_hq``, ``non_uniform_blur`` -> ``non_uniform_blur_grayscale``).
    The translated node is reported as approximated (a warning)."""
    low = name.lower()
    out = []
    if low.endswith("_color"):
        out += [low[:-len("_color")], low[:-len("_color")] + "_grayscale"]
    elif low.endswith("_grayscale"):
        out.append(low[:-len("_grayscale")])
    else:
        out.append(low + "_grayscale")
    return out


SELF_DEPENDENCY = "?himself"


def local_dependency(filename: str | None) -> str | None:
    """The path (relative to its package) of a dependency the translator reads from disk, or None
    for the package itself, Substance's library (``sbs://``) and any other URL, which it does not."""
    if filename is None or filename == SELF_DEPENDENCY or "://" in filename:
        return None
    return filename


def _split_path(path: str) -> tuple[str, str | None]:
    """``pkg:///group/name?dependency=UID`` -> ("group/name", "UID")."""
    body = path.split("://", 1)[1] if "://" in path else path
    body = body.lstrip("/")
    graph, _, query = body.partition("?")
    dep = None
    for part in query.split("&"):
        key, _, value = part.partition("=")
        if key == "dependency":
            dep = value.strip()
    return graph, dep


class Stats:
    def __init__(self) -> None:
        self.total = self.translated = self.passthrough = self.inlined = self.adapters = 0
        self.unsupported: Counter = Counter()
        self.unsupported_functions: Counter = Counter()
        self.warnings: list[str] = []
        self.params_dropped = 0
        self.dropped: Counter = Counter()   # "node.parameter" -> count (parameters the spec lacks)
        self.failed = 0
        self.unconnected_inputs: list[str] = []

    def warn(self, text: str):
        if len(self.warnings) < MAX_WARNINGS:
            self.warnings.append(" ".join(text.split())[:300])


class Builder:
    """Translate one root graph of a package into an IRGraph."""

    def __init__(self, path, mode: str = "exposed_plus", max_bytes: int | None = None):
        self.path = str(path)
        self.mode = mode
        self.stats = Stats()
        self.names: Counter = Counter()
        self.packages: dict[str, Package] = {}
        self.max_bytes = max_bytes
        self.ir: IRGraph | None = None
        self.runtime: dict[str, object] = {}     # exposed name -> default (python)
        self.adapter_cache: dict[tuple, Ref] = {}

    # ---- entry --------------------------------------------------------------------------------
    def build(self, pkg: Package, graph: Graph) -> IRGraph:
        self.packages[os.path.abspath(pkg.path)] = pkg
        ir = self.ir = IRGraph(name=xml_name(graph.identifier, "graph"), mode=self.mode)
        parent = self._parent_size(graph)
        size = self._graph_size(graph, parent)
        ir.size_log2 = size
        env, inputs = self._root_inputs(graph, ir)
        outs = self.translate_graph(pkg, graph, inputs=inputs, env=env, depth=0, parent=parent,
                                    parent_format=0, seed=0, stack=())
        self._root_outputs(graph, outs, ir)
        if not ir.outputs:
            raise TranslatorError(self.path, f"graph {graph.identifier[:60]!r} has no connected output")
        return ir

    def _root_inputs(self, graph: Graph, ir: IRGraph) -> tuple[dict[str, object], dict[str, Ref | None]]:
        """The root graph's inputs: its value parameters exposed on ``ir`` (or, in mode "all",
        their defaults), by identifier, and its image inputs (unconnected)."""
        env: dict[str, object] = {}
        used: set[str] = set()
        inputs: dict[str, Ref | None] = {}
        for i, pi in enumerate(graph.paraminputs):
            if pi.type in IMAGE_TYPES:
                inputs[pi.identifier.lower()] = None
                continue
            entry = TYPE_CODES.get(pi.type) if pi.type is not None else None
            if entry is None:
                continue
            kind, n = entry
            default = _default_value(pi.default, kind, n)
            if self.mode == "all":
                env[pi.identifier] = default
                continue
            name = pi.identifier if SAFE.match(pi.identifier) else f"param_{i}"
            while name in used or name.startswith("$"):
                name = f"param_{i}_{len(used)}"
            used.add(name)
            pyval = default.python()
            if kind == "string" and not (pyval == "" or SAFE.match(pyval)):
                self.stats.warn(f"exposed string {name}: value replaced by an empty string")
                pyval = ""
            lo = pi.min if pi.min is not None else 0.0
            hi = pi.max if pi.max is not None else 1.0
            ir.exposed.append(Exposed(name=name, kind=kind, default=pyval, min=lo, max=hi))
            self.runtime[name] = pyval
            env[pi.identifier] = fgs.getter(kind, n, name)
        return env, inputs

    def _root_outputs(self, graph: Graph, outs: dict, ir: IRGraph):
        """Name ``ir``'s material outputs from the root graph's output usages (the first connected
        output as base colour when none is recognised)."""
        for go in graph.outputs:
            usages = [u.lower() for u in go.usages] or []
            for usage in usages:
                if usage not in USAGES:
                    continue
                if usage in ir.outputs:
                    continue
                ref = outs.get(go.uid)
                if ref is None:
                    self.stats.warn(f"output {usage}: not connected")
                    continue
                ir.outputs[usage] = self.adapt(ref, USAGES[usage])
        if not ir.outputs:  # no recognised usage: show the first connected output as base colour
            for go in graph.outputs:
                ref = outs.get(go.uid)
                if ref is not None:
                    self.stats.warn("no material usage on the graph outputs; the first output is used as basecolor")
                    ir.outputs["basecolor"] = self.adapt(ref, 4)
                    break

    # ---- sizes --------------------------------------------------------------------------------
    @staticmethod
    def _parent_size(graph: Graph) -> tuple[int, int]:
        m = re.match(r"^\s*(\d{1,2})\s*x\s*(\d{1,2})\s*$", graph.options.get("defaultParentSize", ""))
        return (int(m.group(1)), int(m.group(2))) if m else (9, 9)

    def _graph_size(self, graph: Graph, parent) -> tuple[int, int]:
        return self._inherit(graph.base_params.get("outputsize"), parent, None, default_rel=1, two=True)

    def _inherit(self, p: Param | None, parent, primary, default_rel: int, two: bool):
        rel = default_rel
        value = [0, 0] if two else [0]
        if p is not None:
            if p.relative_to in (0, 1, 2):
                rel = p.relative_to
            try:
                if p.constant is not None:
                    value = [int(x) for x in p.constant.numbers()]
                elif p.dynamic is not None:
                    v = fgs.fold(p.dynamic)
                    value = [int(x) for x in (v if isinstance(v, list) else [v])]
            except (BadValue, fgs.FunctionError, TypeError, ValueError):
                pass
            value = fit_components(value, 2 if two else 1)
        base = primary if (rel == 2 and primary is not None) else parent
        if rel == 0:
            out = value
        else:
            out = [b + v for b, v in zip(base, value)] if two else [base[0] + value[0]]
        if two:
            return tuple(max(0, min(14, int(x))) for x in out)
        return max(0, min(3, int(out[0])))

    # ---- names and IR nodes ------------------------------------------------------------------
    def new_name(self, base: str) -> str:
        base = safe_name(base)
        self.names[base] += 1
        name = f"{base}_{self.names[base]}"
        return name if name != "exposed" else self.new_name(base + "_")

    def add(self, node: IRNode) -> IRNode:
        assert self.ir is not None  # set by build() before any node is made
        if len(self.ir.nodes) >= MAX_IR_NODES:
            raise TranslatorError(self.path, f"the translated graph exceeds {MAX_IR_NODES} nodes")
        self.ir.nodes[node.name] = node
        return node

    def uniform(self, channels: int | None, color=GRAY, origin="uniform", status="passthrough",
                size=(9, 9)) -> Ref:
        node = self.add(IRNode(self.new_name("uniform"), "uniform",
                               {"outputcolor": list(color), "colorswitch": channels != 1},
                               origin=origin, status=status, size_log2=size))
        return Ref(node.name, "output", 1 if channels == 1 else 4)

    def adapt(self, ref: Ref, want: int | None) -> Ref:
        """``ref`` converted to ``want`` channels (a pixel processor) when both are known and differ."""
        if want is None or ref.channels is None or ref.channels == want or not has_spec("pixelprocessor"):
            return ref
        key = (ref, want)
        if key not in self.adapter_cache:
            fn = "samplecol" if want == 4 else "samplelum"
            graph = {"nodes": {"0": {"function": "get_float2", "inputs": {}, "data": "$pos"},
                               "1": {"function": fn, "inputs": {"pos": "0"}, "data": {"input": 0, "filtering": 1}}},
                     "root": "1"}
            assert self.ir is not None  # set by build() before any node is made
            src = self.ir.nodes.get(ref.node)
            node = self.add(IRNode(self.new_name("to_color" if want == 4 else "to_gray"), "pixelprocessor",
                                   {"perpixel": fg_engine.dumps(graph), "colorswitch": want == 4},
                                   inputs={"input": ref}, origin="channel conversion", status="adapter",
                                   size_log2=src.size_log2 if src else (9, 9)))
            self.stats.adapters += 1
            self.adapter_cache[key] = Ref(node.name, "output", want)
        return self.adapter_cache[key]

    # ---- one graph ------------------------------------------------------------------------------
    def translate_graph(self, pkg: Package, graph: Graph, *, inputs, env, depth, parent, parent_format,
                        seed, stack) -> dict[str, Ref | None]:
        """Translate ``graph``'s nodes; returns graphoutput uid -> Ref (None when unconnected)."""
        key = (os.path.abspath(pkg.path), graph.uid, graph.path)
        if depth > MAX_DEPTH:
            raise TranslatorError(self.path, f"sub-graph instancing deeper than {MAX_DEPTH} levels")
        if key in stack:
            raise TranslatorError(self.path, f"graph {graph.identifier[:60]!r} instances itself")
        stack = stack + (key,)
        where = f"graph {graph.identifier[:60]!r}"
        order = toposort({uid: [c.source for c in n.connections] for uid, n in graph.nodes.items()},
                         pkg.path, where)
        gsize = self._graph_size(graph, parent)
        gformat = self._inherit(graph.base_params.get("format"), [parent_format], None, 1, False)
        system = {"$size": [float(2 ** gsize[0]), float(2 ** gsize[1])], "$sizelog2": [float(x) for x in gsize],
                  "$normalformat": 0, "$time": 0.0}
        refs: dict[tuple[str, str], Ref | None] = {}
        values: dict[tuple[str, str], object] = {}
        sizes: dict[str, tuple] = {}
        outmap: dict[str, Ref | None] = {}
        pis = {pi.uid: pi for pi in graph.paraminputs}

        for uid in order:
            node = graph.nodes[uid]
            conns = self._connections(graph, node, refs, values, sizes, gsize, where)
            primary = self._primary(conns, sizes)
            size, fmt = self._node_size(node, gsize, gformat, primary)
            sizes[uid] = (size, fmt)
            local = {ident: v for ident, _, v, _ in conns if v is not None}
            node_env = {**system, **env, **local}

            if node.impl == "output":
                assert node.ref is not None  # parse sets ``ref`` on every input / output bridge
                outmap[node.ref] = next((r for _, r, _, _ in conns if r is not None), None)
                continue
            if node.impl == "input":
                assert node.ref is not None  # parse sets ``ref`` on every input / output bridge
                self._input_node(node, pis.get(node.ref), inputs, env, refs, values, size, where)
                continue

            self.stats.total += 1
            if node.impl == "filter":
                self._filter_node(node, conns, node_env, refs, values, size, fmt, seed, where)
            elif node.impl == "instance":
                self._instance(pkg, graph, node, conns, node_env, refs, values, size, fmt, seed, depth,
                               stack, where)
            else:
                self._passthrough(node, node.name or "unknown", conns, refs, size)
        return outmap

    def _connections(self, graph: Graph, node: Node, refs, values, sizes, gsize, where: str) -> list[tuple]:
        """``node``'s connections as (identifier, Ref | None, value | None, source uid); a value
        read by an image slot becomes a uniform image."""
        conns = []
        for c in node.connections:
            src = graph.nodes[c.source]
            out = c.source_output
            known = [o for o, _ in src.outputs]
            if out is None or out not in known:
                if out is not None and known:
                    self.stats.warn(f"{where}: node {node.uid[:20]} reads unknown output {out[:20]}; using the first")
                out = known[0] if known else ""
            ref, value = refs.get((c.source, out)), values.get((c.source, out))
            if ref is None and value is not None and not c.identifier.startswith("#"):
                ref = self._value_image((node.uid, c.source, out), value, sizes.get(c.source, (gsize, 0))[0])
            conns.append((c.identifier, ref, value, c.source))
        return conns

    def _input_node(self, node: Node, pi, inputs, env, refs, values, size, where: str):
        """A graph input node: the image the instance connects (or a uniform one), or the value of
        parameter ``pi``."""
        if pi is None:
            self.stats.warn(f"{where}: input node {node.uid[:20]} refers to an unknown parameter")
            self._set_outputs(node, refs, self.uniform(None, GRAY, "graph input", "input", size))
            return
        if pi.type in IMAGE_TYPES or pi.type is None:
            ref = inputs.get(pi.identifier.lower())
            if ref is None:
                want = IMAGE_TYPES.get(pi.type) or channels_of(node.outputs[0][1] if node.outputs else None)
                self.stats.unconnected_inputs.append(safe_name(pi.identifier, "input"))
                ref = self.uniform(want, GRAY, "graph input", "input", size)
            self._set_outputs(node, refs, ref)
            return
        value = env.get(pi.identifier)
        for o, _ in node.outputs or [("", None)]:
            values[(node.uid, o)] = value

    def _filter_node(self, node: Node, conns, node_env, refs, values, size, fmt, seed, where: str):
        """An atomic node: passthrough, value processor, a registered node, or a passthrough stand-in."""
        fname = node.name.lower()
        if fname == "passthrough":
            self.stats.translated += 1
            ref = next((r for _, r, _, _ in conns if r is not None), None)
            self._set_outputs(node, refs, ref if ref is not None else self.uniform(None, GRAY, size=size))
        elif fname == "valueprocessor":
            self.stats.translated += 1
            value = self._value_function(node, node_env, where)
            for o, _ in node.outputs or [("", None)]:
                values[(node.uid, o)] = value
        elif has_spec(fname):
            self._make(node, get_spec(fname), conns, node_env, refs, size, fmt, seed, where)
        else:
            self._passthrough(node, fname, conns, refs, size)

    def _primary(self, conns, sizes):
        image = [(ident.lower(), src) for ident, ref, _, src in conns if ref is not None]
        for slot in PRIMARY_SLOTS:
            for ident, src in image:
                if ident == slot:
                    return sizes.get(src)
        return sizes.get(image[0][1]) if image else None

    def _node_size(self, node: Node, gsize, gformat, primary):
        connected = primary is not None
        psize, pformat = primary if connected else (None, None)
        size = self._inherit(node.params.get("outputsize"), gsize, psize, 2 if connected else 1, True)
        fmt = self._inherit(node.params.get("format"), [gformat], [pformat] if connected else None,
                            2 if connected else 1, False)
        return size, fmt

    def _set_outputs(self, node: Node, refs, ref: Ref | None):
        for o, ct in node.outputs or [("", None)]:
            refs[(node.uid, o)] = self.adapt(ref, channels_of(ct)) if ref is not None else None

    # ---- passthrough ----------------------------------------------------------------------------
    def _passthrough(self, node: Node, name: str, conns, refs, size):
        self.stats.passthrough += 1
        self.stats.unsupported[report_name(name)] += 1
        name = xml_name(name, "unknown")
        src = next((r for _, r, _, _ in conns if r is not None), None)
        made: dict[int | None, Ref] = {}
        for o, ct in node.outputs or [("", None)]:
            want = channels_of(ct)
            if want not in made:
                if src is None:
                    made[want] = self.uniform(want, stand_in_colour(name), origin=name, size=size)
                elif want is None or src.channels is None or want == src.channels:
                    ir = self.add(IRNode(self.new_name("passthrough"), "passthrough", inputs={"input": src},
                                         origin=name, status="passthrough", size_log2=size))
                    made[want] = Ref(ir.name, "output", src.channels or want)
                else:
                    made[want] = self.adapt(src, want)
                    assert self.ir is not None  # set by build() before any node is made
                    self.ir.nodes[made[want].node].status = "passthrough"
                    self.ir.nodes[made[want].node].origin = name
            refs[(node.uid, o)] = made[want]

    # ---- values ---------------------------------------------------------------------------------
    def _compose(self, graph: dict, env: dict, where: str, pixel: bool = False) -> dict | None:
        """Substitute ``env`` into ``graph``; None (reported) if it reads anything else."""
        allowed = set(env) | (set(fg_engine.SYSTEM_VARIABLES) if pixel else set())
        unknown = fgs.free_variables(graph) - allowed
        if unknown:
            self.stats.warn(f"{where}: reads unknown variable(s) {sorted(safe_name(u, 'var') for u in unknown)[:5]}")
            return None
        try:
            out = fgs.substitute(graph, {k: v for k, v in env.items() if v is not None})
        except fgs.FunctionError as exc:
            self.stats.warn(f"{where}: {exc}")
            return None
        out = fgs.sanitize_strings(out)
        leftover = fgs.free_variables(out) - set(self.runtime) - (set(fg_engine.SYSTEM_VARIABLES) if pixel else set())
        if leftover:
            self.stats.warn(f"{where}: reads unset variable(s)")
            return None
        return out

    def _value_function(self, node: Node, env, where):
        p = node.params.get("function")
        if p is None or p.dynamic is None:
            if p is not None and p.error:
                self._function_error(p.error)
            return None
        return self._compose(p.dynamic, env, f"{where}: value processor {node.uid[:20]}")

    def _value_image(self, key, value, size) -> Ref | None:
        """A value output read as an image: a Value Processor node (a uniform image of the value,
        exposed parameters at their defaults)."""
        if key in self.adapter_cache:
            return self.adapter_cache[key]
        graph = value if isinstance(value, dict) else fgs.constant_graph(
            {"float": "get_float", "int": "get_integer"}.get(value.kind, "get_float") + str(value.n)
            if value.kind in ("float", "int") else "get_" + value.kind, value)
        try:
            graph = fgs.substitute(graph, self.runtime)
            result = self._fold(graph, 0)
        except fgs.FunctionError as exc:
            self.stats.warn(f"value output read as an image: {exc}")
            return None
        if isinstance(result, str) or not has_spec("valueprocessor"):
            return None
        n = len(result) if isinstance(result, list) else 1
        node = self.add(IRNode(self.new_name("valueprocessor"), "valueprocessor",
                               {"function": fg_engine.dumps(graph)}, origin="value output",
                               status="adapter", size_log2=size))
        self.adapter_cache[key] = Ref(node.name, "output", 1 if n == 1 else 4)
        return self.adapter_cache[key]

    def _function_error(self, error: str):
        m = re.match(r"unsupported function '([^']*)'", error)
        self.stats.unsupported_functions[safe_name(m.group(1), "function") if m else "malformed"] += 1

    def _fold(self, graph: dict, seed: int):
        return fgs.fold(graph, self.runtime, seed=seed)

    # ---- a registered node --------------------------------------------------------------------
    def _make(self, node: Node, spec, conns, env, refs, size, fmt, seed, where, origin=None):
        ir = IRNode(self.new_name(spec.name), spec.name, origin=xml_name(origin or spec.name, "library_node"),
                    size_log2=size, format=fmt)
        label = f"{where}: {spec.name} {node.uid[:20]}"
        own_types = {channels_of(ct) for _, ct in node.outputs}
        own = own_types.pop() if len(own_types) == 1 and len(spec.outputs) == 1 else None
        self._make_inputs(ir, spec, conns, own, size, label)
        node_seed = seed
        if "randomseed" in node.params:
            node_seed = self._seed(node.params["randomseed"], seed, label)
        self._make_params(ir, node, spec, env, label, node_seed)
        if ("colorswitch" in spec.param_index and "colorswitch" not in ir.params and own is not None
                and spec.param("colorswitch").kind == "bool"):
            ir.params["colorswitch"] = own == 4  # the file omits it: follow the output's recorded type
        for array, cells in node.arrays.items():
            self._array(ir, spec, array, cells, label)
        ir.seed = node_seed
        self.add(ir)
        self.stats.translated += 1
        self._make_outputs(ir, node, spec, refs, label)
        return ir

    def _make_inputs(self, ir: IRNode, spec, conns, own: int | None, size, label: str):
        """Connect ``ir``'s input slots (by alias), adapted to the slots' channels (a variant node
        follows its own output's recorded type); an unconnected required slot gets a uniform image."""
        slots = {s.name: s for s in spec.inputs}
        image_conns = [(i, r) for i, r, _, _ in conns if r is not None]
        variant = own is not None and spec.kind != "generator" and spec.name not in NOT_VARIANT
        for ident, ref in image_conns:
            slot = aliases.resolve_input(spec, ident) or ident.lower().replace(":", "_")
            if slot not in slots and len(spec.inputs) == 1 and len(image_conns) == 1:
                slot = spec.inputs[0].name
            if slot not in slots:
                self.stats.warn(f"{label}: no input {safe_name(ident, 'slot')!r}; connection dropped")
                continue
            want = {"gray": 1, "color": 4}.get(slots[slot].channels, own if variant else None)
            ir.inputs[slot] = self.adapt(ref, want)
        for s in spec.inputs:
            if s.name not in ir.inputs and not s.optional:
                want = {"gray": 1, "color": 4}.get(s.channels, own or 4)
                ir.inputs[s.name] = self.uniform(want, UNCONNECTED, origin="unconnected input", status="input",
                                                 size=size)

    def _make_params(self, ir: IRNode, node: Node, spec, env, label: str, node_seed: int):
        """Convert ``node``'s parameters to ``ir``'s (exact identifiers first, then aliases)."""
        pixel = spec.name == "pixelprocessor"
        aliased = []
        for pname, p in node.params.items():
            if pname == "randomseed" or (pname in BASE_PARAMS and pname not in spec.param_index):
                continue
            targets = aliases.resolve_param(spec, pname)
            if not targets:
                self.stats.params_dropped += 1
                self.stats.dropped[f"{spec.name}.{report_name(pname)}"] += 1
                continue
            if targets == [(pname, None)]:
                self._param(ir, spec.param(pname), p, env, label, pixel, node_seed)
            else:
                aliased.append((pname, p, targets))
        for pname, p, targets in aliased:  # exact identifiers win over aliases
            for target, component in targets:
                if target not in ir.params and target not in ir.bindings:
                    self._param(ir, spec.param(target), p, env, label, pixel, node_seed,
                                component=component, ident=pname)

    def _make_outputs(self, ir: IRNode, node: Node, spec, refs, label: str):
        """Map ``node``'s outputs to ``ir``'s (by bridging identifier, else by position)."""
        outputs = list(spec.outputs)
        for i, (o, ct) in enumerate(node.outputs or [("", None)]):
            name = None
            ident = node.bridgings.get(o)
            if ident is not None and ident.lower() in outputs:
                name = ident.lower()
            elif len(outputs) == 1:
                name = outputs[0]
            elif i < len(outputs):
                name = outputs[i]
                self.stats.warn(f"{label}: output {safe_name(ident or '', 'output')!r} taken as {name!r}")
            else:
                name = outputs[0]
                self.stats.warn(f"{label}: output {safe_name(ident or '', 'output')!r} unknown; using {name!r}")
            refs[(node.uid, o)] = Ref(ir.name, name, channels_of(ct))

    def _seed(self, p: Param, base: int, label: str) -> int:
        try:
            if p.constant is not None:
                value = int(p.constant.numbers()[0])
            elif p.dynamic is not None:
                v = self._fold(p.dynamic, 0)
                value = int(v[0] if isinstance(v, list) else v)
            else:
                return base
        except (BadValue, fgs.FunctionError, TypeError, ValueError):
            self.stats.warn(f"{label}: bad random seed")
            return base
        return (base + value if p.relative_to == 1 else value) % (2 ** 31)

    def _param(self, ir: IRNode, sp, p: Param, env, label, pixel: bool, seed: int,
               component: int | None = None, ident: str | None = None):
        where = f"{label}.{sp.name}"
        spec_name = ir.spec
        ident = ident or sp.name
        if p.error:
            self._function_error(p.error)
            self.stats.warn(f"{where}: {p.error}; default kept")
            return
        if p.constant is not None:
            value = p.constant
            if pixel and sp.name == "perpixel":
                self.stats.warn(f"{where}: constant function; default kept")
                return
            try:
                ir.params[sp.name] = convert(sp, _adjust(value.python(), spec_name, sp.name, ident, component))
            except ClampedValue as exc:
                ir.params[sp.name] = exc.value
                self.stats.warn(f"{where}: {exc}")
            except BadValue as exc:
                self.stats.warn(f"{where}: {exc}; default kept")
            return
        perpixel = pixel and sp.name == "perpixel"
        if perpixel:  # the pixel processor provides $pos, $size, ... itself
            env = {k: v for k, v in env.items() if not k.startswith("$")}
        assert p.dynamic is not None  # parse sets either an error, a constant or a function graph
        graph = self._compose(p.dynamic, env, where, pixel=perpixel)
        if graph is None:
            return
        if perpixel:
            graph = fgs.substitute(graph, self.runtime)  # exposed parameters at their defaults
            ir.params[sp.name] = fg_engine.dumps(graph)
            return
        try:
            raw = self._fold(graph, seed)
            adjusted = _adjust(raw, spec_name, sp.name, ident, component)
            value = convert(sp, adjusted)
        except ClampedValue as exc:  # unbound: the function would give the value past the range again
            ir.params[sp.name] = exc.value
            self.stats.warn(f"{where}: {exc}")
            return
        except (fgs.FunctionError, BadValue, TypeError, ValueError) as exc:
            self.stats.warn(f"{where}: {exc}; default kept")
            return
        ir.params[sp.name] = value
        rescaled = component is not None or adjusted is not raw
        # a parameter a function drives is no slider in Substance: outside mode "all" it stays
        # bound, constant functions included, so that it is never optimised (a dielectric's
        # metallic 0 must not drift)
        if self.mode != "all" and sp.kind != "string" and not rescaled:
            ir.bindings[sp.name] = graph

    def _array(self, ir: IRNode, spec, array: str, cells, label):
        """Parameter arrays (gradient keys, curve points): each cell field becomes a list-valued
        parameter of the spec, cells sorted by position (names tried: ARRAY_FIELD, FIELDs, FIELD)."""
        cells = [c for c in cells if c]
        if not cells:
            return
        try:
            cells.sort(key=lambda c: c["position"].numbers()[0] if "position" in c else 0.0)
        except BadValue:
            return
        fields = sorted({f for c in cells for f in c})
        used = False
        for f in fields:
            for cand in (f"{array}_{f}", f"{f}s", f, {"value": "colors"}.get(f, "")):
                if cand and cand in spec.param_index and spec.param(cand).kind == "float":
                    try:
                        nums = [x for c in cells if f in c for x in c[f].numbers()]
                        ir.params[cand] = convert(spec.param(cand), nums)
                        used = True
                    except BadValue as exc:
                        self.stats.warn(f"{label}: {array}.{f}: {exc}")
                    break
        if not used:
            self.stats.warn(f"{label}: parameter array {safe_name(array, 'array')!r} not supported; default kept")

    # ---- instances ------------------------------------------------------------------------------
    def _instance(self, pkg, graph, node, conns, env, refs, values, size, fmt, seed, depth, stack, where):
        gpath, dep = _split_path(node.name)
        gname = gpath.rsplit("/", 1)[-1]
        filename = pkg.dependencies.get(dep) if dep is not None else None
        if filename is None and dep is None and gpath:
            filename = SELF_DEPENDENCY
        local = local_dependency(filename)
        if filename == SELF_DEPENDENCY or local is not None:
            sub_pkg = pkg if local is None else self._load_dependency(pkg, local)
            sub = sub_pkg.find_graph(gpath) or sub_pkg.find_graph(gname)
            if sub is not None:
                self._inline(sub_pkg, sub, node, conns, env, refs, size, fmt, seed, depth, stack)
                return
            if filename == SELF_DEPENDENCY or not has_spec(gname.lower()):
                self.stats.warn(f"{where}: graph {safe_name(gname, 'graph')!r} not found in its package")
        for cand in _library_candidates(gname, filename):
            if has_spec(cand):
                self._make(node, get_spec(cand), conns, env, refs, size, fmt, seed, where, origin=gname)
                return
        for cand in _variant_candidates(gname):
            if has_spec(cand) and get_spec(cand).kind != "generator":
                self.stats.warn(f"{where}: {safe_name(gname, 'graph')!r} approximated by {cand!r}")
                self._make(node, get_spec(cand), conns, env, refs, size, fmt, seed, where, origin=gname)
                return
        self._passthrough(node, gname, conns, refs, size)

    def _load_dependency(self, pkg: Package, filename: str) -> Package:
        base = os.path.dirname(os.path.abspath(pkg.path))
        target = os.path.abspath(os.path.join(base, filename))
        if target in self.packages:
            return self.packages[target]
        if not os.path.isfile(target):
            raise TranslatorError(self.path, f"missing dependency file {os.path.basename(filename)[:80]!r}")
        if len(self.packages) > 64:
            raise TranslatorError(self.path, "too many dependency files")
        root = read_document(target, self.max_bytes or MAX_BYTES)
        sub = load_package(target, root)
        self.packages[target] = sub
        return sub

    def _inline(self, sub_pkg, sub: Graph, node: Node, conns, env, refs, size, fmt, seed, depth, stack):
        self.stats.inlined += 1
        self.stats.translated += 1
        sub_env: dict[str, object] = {}
        inputs: dict[str, Ref | None] = {}
        image_conns = {ident.lower(): r for ident, r, _, _ in conns if r is not None}
        node_seed = seed
        if "randomseed" in node.params:
            node_seed = self._seed(node.params["randomseed"], seed, f"instance {node.uid[:20]}")
        for pi in sub.paraminputs:
            low = pi.identifier.lower()
            if pi.type in IMAGE_TYPES:
                inputs[low] = image_conns.get(low)
                continue
            entry = TYPE_CODES.get(pi.type) if pi.type is not None else None
            if entry is None:
                continue
            kind, n = entry
            p = node.params.get(low)
            value: object = _default_value(pi.default, kind, n)
            if p is not None and p.constant is not None:
                value = p.constant
            elif p is not None and p.dynamic is not None:
                composed = self._compose(p.dynamic, env, f"instance {node.uid[:20]}.{safe_name(low, 'param')}")
                if composed is not None:
                    value = composed
            sub_env[pi.identifier] = value
        outs = self.translate_graph(sub_pkg, sub, inputs=inputs, env=sub_env, depth=depth + 1, parent=size,
                                    parent_format=fmt, seed=node_seed, stack=stack)
        by_ident = {go.identifier.lower(): go.uid for go in sub.outputs}
        first = next((outs.get(go.uid) for go in sub.outputs if outs.get(go.uid) is not None), None)
        for o, ct in node.outputs or [("", None)]:
            ident = node.bridgings.get(o, "").lower()
            ref = outs.get(by_ident.get(ident, ""), None) if ident in by_ident else first
            if ref is None:
                ref = self.uniform(channels_of(ct), GRAY, origin="unconnected output", size=size)
            refs[(node.uid, o)] = self.adapt(ref, channels_of(ct))


def _default_value(value: Value | None, kind: str, n: int) -> Value:
    """A paraminput's default as a Value of (kind, n); zero / false / "" when missing or mistyped."""
    if value is not None and value.kind == kind:
        if kind in ("float", "int"):
            return Value(kind, n, tuple(fit_components(value.numbers(), n)))
        return value
    if value is not None and kind in ("float", "int") and value.kind in ("float", "int", "bool"):
        nums = value.numbers()
        nums = [float(x) if kind == "float" else int(x) for x in nums]
        return Value(kind, n, tuple(fit_components(nums, n)))
    if kind == "string":
        return Value("string", 1, "")
    if kind == "bool":
        return Value("bool", 1, False)
    return Value(kind, n, tuple([0.0 if kind == "float" else 0] * n))


def _adjust(value, spec_name: str, param: str, ident: str, component: int | None):
    """The file value's ``component`` (when an alias spreads a vector over several parameters),
    rescaled where the library's meaning differs from the spec's (aliases.convert_value)."""
    if component is not None:
        if not isinstance(value, (list, tuple)):
            raise BadValue("a vector value is expected")
        if component >= len(value):
            raise BadValue(f"the value has no component {component}")
        value = value[component]
    return aliases.convert_value(spec_name, param, ident, value)


def convert(sp, value):
    """A file value (number, list, bool or str) as a value of the spec parameter ``sp``;
    BadValue when it does not fit (the caller keeps the default), ClampedValue for an integer past
    the parameter's range (the caller takes the nearest in range)."""
    if sp.kind == "string":
        if isinstance(value, str) and (value == "" or SAFE.match(value)):
            return value
        raise BadValue("a string parameter is kept only when it is a plain identifier")
    if isinstance(value, str):
        raise BadValue("a string where a number is expected")
    nums = value if isinstance(value, list) else [value]
    nums = [float(x) for x in nums]
    if not nums or not all(math.isfinite(x) for x in nums):
        raise BadValue("value is not finite")
    if sp.kind == "float":
        out = fit_components(nums, sp.size, sp.default)
        return out[0] if sp.size == 1 else out
    if sp.kind == "bool":
        return bool(nums[0] >= 0.5)
    x = int(round(nums[0]))
    if sp.kind == "enum" and x not in sp.choices:
        raise BadValue(f"value {x} is not one of {list(sp.choices)}")
    if sp.kind == "int" and not sp.min <= x <= sp.max:
        nearest = int(min(max(x, sp.min), sp.max))
        raise ClampedValue(f"value {x} is outside [{sp.min:g}, {sp.max:g}]; {nearest} used", nearest)
    return x


__all__ = ["Builder", "convert", "safe_name", "xml_name"]
