"""Build the shipped library files from the material sources.

    python -m blender_match.library.build [NAME ...] [--check]

For every module in ``blender_match/library/sources/`` (or only the NAMEs given) this builds the
source graph, writes it as ``blender_match/library/graphs/<name>.sbs`` (``sbs_export``), reads the
file back with the translator (``load_sbs_graph``, mode exposed_plus) and writes
``graphs/<name>.json``, the metadata:

- ``name``, ``file`` (the .sbs file name), ``description`` (the source docstring's first line);
- ``nodes`` (nodes of the translated graph), ``params_optimizable`` (its optimisable values in mode
  exposed_plus), ``exposed`` (exposed parameter names), ``exposed_params`` (kind, default, range);
- ``sample_ranges``: ``{"node.param": [lo, hi]}`` for EVERY optimisable parameter, keyed by the
  parameter names of the translated graph (``exposed.NAME`` for exposed ones); a vector parameter
  has per-component lists. The source's ``SAMPLE_RANGES`` (keyed by the source's node names, which
  the translator renames) give some; the others get the authored value +- 15% of the parameter's
  full range, at most +- (half the value + 1% of the range) (``default_spread``), clamped to it
  (except a blend's ``maskrectangle``, kept at its authored value unless listed: a sampled crop
  rectangle cuts a non-tiling hole in a layer);
- ``sample_together``: the vector parameters given that default spread (colours the source did not
  list): their components are drawn with one shared fraction of their ranges, so a grey stays grey
  in every variant instead of taking a random tint (a listed range is drawn per component: an
  author who lists one means the components to vary apart, as a dye of any hue does, unless the
  source's ``SAMPLE_TOGETHER`` names it: a listed line of colours, dark walnut to blond wood);
- ``node_names``: source node name -> translated node name.

It refuses a source whose round trip is not exact in structure (the translated graph must be the
source graph node for node: same node types, same connections, no pass-through). ``--check``
writes nothing and exits 1 if a shipped file differs from what the sources give.
"""
from __future__ import annotations

import argparse
import json
import sys
import tempfile
from pathlib import Path

from ..diffmat.errors import DiffMatError
from ..errors import BlenderMatchError
from ..safe_files import json_text, write_atomic
from ..translator import load_sbs_graph
from . import FAMILIES, GRAPHS_DIR, build_source, source_module, source_names
from .sbs_export import export_sbs

DEFAULT_SPREAD = 0.15
# layout parameters whose default range is the authored value only (a sampled blend crop rectangle
# would cut a hard-edged, non-tiling rectangle out of a layer); a source may still list them
FIXED_BY_DEFAULT = {("blend", "maskrectangle")}


def match_nodes(source, translated) -> dict[str, str]:
    """Source node name -> translated node name, by walking both graphs from their outputs.
    DiffMatError when they differ in structure. Source ``passthrough`` (dot) nodes, which the
    translator forwards, have no counterpart and are skipped."""
    mapping: dict[str, str] = {}
    if set(source.outputs) != set(translated.outputs):
        raise DiffMatError(f"{source.name}: outputs {sorted(source.outputs)} became {sorted(translated.outputs)}")
    stack = [(source.outputs[u], translated.outputs[u], u) for u in source.outputs]
    while stack:
        (sn, so), (tn, to), where = stack.pop()
        snode, tnode = source.nodes[sn], translated.nodes[tn]
        if snode.spec.name == "passthrough" and tnode.spec.name != "passthrough":
            # a dot node: the translator forwards its input (Substance's "passthrough" filter)
            if source.links[sn][0] is None:
                raise DiffMatError(f"{source.name}: pass-through node {sn} has no input")
            stack.append((source.links[sn][0], (tn, to), where))
            continue
        if snode.spec.name != tnode.spec.name or so != to:
            raise DiffMatError(f"{source.name}: node {sn} ({snode.spec.name}:{so}) came back as "
                               f"{tn} ({tnode.spec.name}:{to}) (reached from {where})")
        if sn in mapping:
            if mapping[sn] != tn:
                raise DiffMatError(f"{source.name}: node {sn} came back as both {mapping[sn]} and {tn}")
            continue
        mapping[sn] = tn
        for slot, sref, tref in zip(snode.spec.inputs, source.links[sn], translated.links[tn]):
            if (sref is None) != (tref is None):
                raise DiffMatError(f"{source.name}: input {sn}.{slot.name} changed connection in the round trip")
            if sref is not None:
                stack.append((sref, tref, f"{sn}.{slot.name}"))
    if len(set(mapping.values())) != len(mapping) or len(translated.nodes) != len(mapping):
        extra = sorted(set(translated.nodes) - set(mapping.values()))
        raise DiffMatError(f"{source.name}: the translated graph has nodes the source has not: {extra[:5]}")
    return mapping


def _real(t) -> list[float]:
    return [float(x) for x in t.detach().reshape(-1)]


def sample_ranges(translated, mapping: dict[str, str], declared: dict, name: str, declared_together=()) -> dict:
    """``{"sample_ranges", "sample_together"}`` of the translated graph's optimisable parameters
    (see the module doc); ``declared_together`` (the source's ``SAMPLE_TOGETHER``): listed vector
    parameters whose components are drawn with one shared fraction of their ranges all the same."""
    out: dict[str, list] = {}
    slots, listed = {}, set()
    exposed_values = translated.exposed.values()
    for n, p, k in translated.param_slots():
        if n == "exposed":
            value, (lo, hi) = _real(exposed_values[p]), translated.exposed.ranges[p]
        else:
            value, (lo, hi) = _real(translated.nodes[n].values()[p]), translated.nodes[n].ranges[p]
        slots[f"{n}.{p}"] = (value, lo, hi)
        fixed = n != "exposed" and (translated.nodes[n].spec.name, p) in FIXED_BY_DEFAULT
        spreads = [0.0 if fixed else default_spread(v, lo, hi) for v in value]
        los = [max(lo, v - d) for v, d in zip(value, spreads)]
        his = [min(hi, v + d) for v, d in zip(value, spreads)]
        out[f"{n}.{p}"] = [los[0], his[0]] if len(value) == 1 else [los, his]
    for key, rng in declared.items():
        node, _, param = key.partition(".")
        tkey = key if node == "exposed" else f"{mapping.get(node, '?')}.{param}"
        if tkey not in slots:
            raise DiffMatError(f"sources/{name}.py: SAMPLE_RANGES names {key!r}, which is not an optimisable "
                               "parameter (unknown, discrete or bound to exposed parameters)")
        value, plo, phi = slots[tkey]
        try:
            lo, hi = rng
        except (TypeError, ValueError):
            raise DiffMatError(f"sources/{name}.py: SAMPLE_RANGES[{key!r}] must be (lo, hi)") from None
        k = len(value)
        los = [float(x) for x in (lo if isinstance(lo, (list, tuple)) else [lo] * k)]
        his = [float(x) for x in (hi if isinstance(hi, (list, tuple)) else [hi] * k)]
        if len(los) != k or len(his) != k:
            raise DiffMatError(f"sources/{name}.py: SAMPLE_RANGES[{key!r}] needs {k} component(s)")
        for a, b in zip(los, his):
            if not (plo - 1e-6 <= a <= b <= phi + 1e-6):
                raise DiffMatError(f"sources/{name}.py: SAMPLE_RANGES[{key!r}] = {rng!r} is not an interval "
                                   f"inside the parameter's range [{plo:g}, {phi:g}]")
        los = [max(plo, a) for a in los]
        his = [min(phi, b) for b in his]
        out[tkey] = [los[0], his[0]] if k == 1 else [los, his]
        if key not in declared_together:
            listed.add(tkey)
    unknown = sorted(set(declared_together) - set(declared))
    if unknown:
        raise DiffMatError(f"sources/{name}.py: SAMPLE_TOGETHER names {', '.join(unknown)}, not in SAMPLE_RANGES")
    together = sorted(key for key, (value, _, _) in slots.items() if len(value) > 1 and key not in listed)
    return {"sample_ranges": {k: _rounded(v) for k, v in sorted(out.items())}, "sample_together": together}


def default_spread(value: float, lo: float, hi: float) -> float:
    """How far an unlisted parameter is sampled either side of its authored value: 15% of its range,
    but no more than half the value's size plus 1% of the range, so that a value small on a wide
    scale (a warp of 0.04 out of 0-20, a rotation of 0) varies around itself instead of by several
    times itself (up to 3.0 for that warp, which destroys the pattern it shapes)."""
    return min(DEFAULT_SPREAD * (hi - lo), 0.5 * abs(value) + 0.01 * (hi - lo))


def _rounded(rng):
    def r(x):
        return [round(v, 6) for v in x] if isinstance(x, list) else round(x, 6)
    lo, hi = r(rng[0]), r(rng[1])
    return [lo, hi]


def graph_summary(translated) -> dict:
    """The metadata every library entry has from its translated graph: ``nodes``,
    ``params_optimizable``, ``exposed``, ``exposed_params`` (kind, default, range), ``bindings`` and
    ``outputs``."""
    ex = translated.exposed
    exposed_params: dict[str, dict[str, object]] = {}
    values = ex.values()
    for pname, kind in ex.kinds.items():
        info: dict[str, object] = {"kind": kind}
        if kind == "float":
            v = _real(values[pname])
            info["default"] = [round(x, 6) for x in v] if len(v) > 1 else round(v[0], 6)
            info["min"], info["max"] = [round(x, 6) for x in ex.ranges[pname]]
        else:
            info["default"] = values[pname]
        exposed_params[pname] = info
    return {"nodes": len(translated.nodes), "params_optimizable": translated.num_params(), "exposed": list(ex.kinds),
            "exposed_params": exposed_params, "bindings": translated.report["bindings"],
            "outputs": sorted(translated.outputs)}


def build_one(name: str) -> tuple[str, str]:
    """(sbs text, metadata json text) of source ``name``."""
    module = source_module(name)
    doc = (module.__doc__ or "").strip()
    if not doc:
        raise DiffMatError(f"sources/{name}.py: a material source needs a docstring")
    declared = getattr(module, "SAMPLE_RANGES", None)
    if not isinstance(declared, dict):
        raise DiffMatError(f"sources/{name}.py: SAMPLE_RANGES must be a dict")
    family = getattr(module, "FAMILY", None)
    if family not in FAMILIES:
        raise DiffMatError(f"sources/{name}.py: FAMILY must be one of {', '.join(FAMILIES)}, not {family!r}")
    graph = build_source(name)
    description = doc.splitlines()[0].strip()
    text = export_sbs(graph, description)
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / f"{name}.sbs"
        path.write_text(text, encoding="utf-8")
        translated = load_sbs_graph(path)
    report = translated.report
    if report["nodes_passthrough"]:
        raise DiffMatError(f"sources/{name}.py: {report['nodes_passthrough']} node(s) translate as pass-through "
                           f"({report['unsupported']})")
    mapping = match_nodes(graph, translated)
    meta = {"name": name, "file": f"{name}.sbs", "description": description, "family": family,
            **graph_summary(translated),
            **sample_ranges(translated, mapping, declared, name, getattr(module, "SAMPLE_TOGETHER", ())),
            "node_names": dict(sorted(mapping.items()))}
    return text, json_text(meta)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m blender_match.library.build", description=__doc__.splitlines()[0])
    parser.add_argument("names", nargs="*", help="sources to build (default: all)")
    parser.add_argument("--check", action="store_true", help="only check that the shipped files are up to date")
    args = parser.parse_args(argv)
    names = args.names or source_names()
    failed = stale = 0
    for name in names:
        try:
            sbs, meta = build_one(name)
        except (BlenderMatchError, ValueError, OSError, ImportError, AttributeError, TypeError) as exc:
            print(f"{name}: FAILED: {exc}", file=sys.stderr)
            failed += 1
            continue
        files = {GRAPHS_DIR / f"{name}.sbs": sbs, GRAPHS_DIR / f"{name}.json": meta}
        if args.check:
            for path, text in files.items():
                if not path.is_file() or path.read_text(encoding="utf-8") != text:
                    print(f"{path}: out of date")
                    stale += 1
            continue
        for path, text in files.items():
            write_atomic(path, text.encode("utf-8"), overwrite=True)
        info = json.loads(meta)
        print(f"{name:<16} nodes {info['nodes']:>4}  params {info['params_optimizable']:>4}  "
              f"exposed {len(info['exposed'])}")
    return 1 if failed or stale else 0


if __name__ == "__main__":
    sys.exit(main())
