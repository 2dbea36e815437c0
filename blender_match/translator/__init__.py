"""Translator from Substance .sbs documents to DiffMat graphs (the MATch paper, section 5.7).

Steps, one module each: safe XML reading (``xml_safety``), parsing into a model (``parse``,
``values``, ``function_graphs``), graph replication and parameter conversion (``build``), data-flow
analysis and topological sort (``dataflow``), the runnable graph (``assemble``, ``runtime``),
program generation (``codegen``) and the coverage report (``report``).

Exposed parameters (design choice; see ``runtime``): the root graph's exposed parameters become
graph-level parameters of an ``SbsGraph`` (a MaterialGraph). In modes "exposed" and
"exposed_plus", a node parameter given by a function graph of exposed parameters is *bound*: the
function graph is re-evaluated with torch from the exposed values at every forward pass, so it is
differentiable in them, and the node parameter itself is not optimisable. Mode "exposed" frees
only the exposed parameters; "exposed_plus" also every unbound node parameter; "all" folds every
function graph into a constant at translation time and frees every node parameter (no exposed
parameters remain). Pixel-processor functions read exposed parameters at their defaults.

Value outputs (value processors, value inputs) are function graphs substituted into the function
graphs that read them (``#pin`` connections), so they stay functions of the exposed parameters;
one read as an image becomes a Value Processor node (a uniform image of the value).

Entry points: ``translate(path, graph_name, mode)`` -> ``Translation`` (graph, program, report),
``load_sbs_graph(path, graph_name=None, mode="exposed_plus")`` -> the MaterialGraph (its report is
``graph.report``). Every problem with the file is a ``TranslatorError`` (a ValueError).
"""
from __future__ import annotations

import os
import time
from dataclasses import dataclass

from ..errors import BlenderMatchError
from . import dataflow
from .assemble import assemble, finalize
from .build import USAGES, Builder, local_dependency, xml_name
from .codegen import generate
from .errors import TranslatorError
from .parse import load_package
from .probe import probe
from .report import make_report
from .runtime import MODES, SbsGraph
from .xml_safety import MAX_BYTES, read_document

__all__ = ["TranslatorError", "Translation", "translate", "load_sbs_graph", "local_dependencies", "SbsGraph", "MODES"]


@dataclass
class Translation:
    graph: SbsGraph
    program: str
    report: dict


def _pick_graph(pkg, graph_name, path):
    if graph_name is not None:
        g = pkg.find_graph(graph_name)
        if g is None:
            names = ", ".join(x.identifier[:40] for x in pkg.graphs[:10])
            raise TranslatorError(path, f"no graph named {graph_name[:60]!r} (graphs: {names or 'none'})")
        return g
    for g in pkg.graphs:
        if any(u.lower() in USAGES for o in g.outputs for u in o.usages):
            return g
    for g in pkg.graphs:
        if g.outputs:
            return g
    raise TranslatorError(path, "the package holds no graph with outputs")


def translate(path, graph_name: str | None = None, mode: str = "exposed_plus", *,
              max_bytes: int | None = None) -> Translation:
    """Translate one graph of the .sbs file at ``path``."""
    if mode not in MODES:
        raise TranslatorError(path, f"unknown mode {mode!r}; expected one of {list(MODES)}")
    start = time.perf_counter()
    try:
        root = read_document(path, max_bytes or MAX_BYTES)
        pkg = load_package(path, root)
        graph = _pick_graph(pkg, graph_name, path)
        builder = Builder(path, mode, max_bytes=max_bytes)
        ir = builder.build(pkg, graph)
        statuses = {n: node.status for n, node in ir.nodes.items()}
        pruned_counted = [n for n in dataflow.prune(ir) if statuses[n] in ("translated", "passthrough")]
        finalize(ir, builder.stats.warn)
        order = probe(builder, dataflow.order(ir, path))
        sbs_graph = assemble(ir, order)
        program = generate(ir, order, xml_name(os.path.splitext(os.path.basename(str(path)))[0], "sbs_file"))
    except TranslatorError:
        raise
    except RecursionError:
        raise TranslatorError(path, "document nested too deeply") from None
    except (BlenderMatchError, KeyError, IndexError, TypeError, AttributeError, ValueError, OverflowError,
            ZeroDivisionError, RuntimeError) as exc:
        raise TranslatorError(path, f"cannot translate ({type(exc).__name__}: {exc})") from None
    report = make_report(path=str(path), ir=ir, stats=builder.stats, pruned=pruned_counted,
                         params_optimizable=sbs_graph.num_params(), seconds=time.perf_counter() - start,
                         graphs=[g.identifier for g in pkg.graphs])
    sbs_graph.report = report
    return Translation(sbs_graph, program, report)


def local_dependencies(path) -> list[str]:
    """The local files (relative paths, as the document writes them) that the .sbs file at
    ``path`` and, recursively, the ones among them that exist name as dependencies: those the
    translator reads from disk (``build.local_dependency``); ``sbs://`` references to Substance's
    own library, which the engine implements, are not listed."""
    seen: dict[str, str] = {}
    stack = [(os.path.abspath(str(path)), "")]
    while stack:
        file, prefix = stack.pop()
        pkg = load_package(file, read_document(file, MAX_BYTES))
        for name in pkg.dependencies.values():
            ref = local_dependency(name)
            if ref is None:
                continue
            relative = os.path.normpath(os.path.join(prefix, ref))
            target = os.path.abspath(os.path.join(os.path.dirname(file), ref))
            if relative not in seen:
                seen[relative] = target
                if os.path.isfile(target) and len(seen) <= 64:
                    stack.append((target, os.path.dirname(relative)))
    return sorted(seen)


def load_sbs_graph(path, graph_name: str | None = None, mode: str = "exposed_plus") -> SbsGraph:
    """The MaterialGraph (an SbsGraph) of one graph of an .sbs file; its coverage report is
    ``graph.report`` (a dict, as written by ``blender-match translate --report``)."""
    return translate(path, graph_name, mode).graph
