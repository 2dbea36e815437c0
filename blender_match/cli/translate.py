"""``blender-match translate GRAPH.sbs``: translate a Substance graph into a DiffMat program.

Writes ``<graph>.py`` (a module whose ``build()`` rebuilds the graph with DiffMat calls) into
``--out`` (default: the current directory), and a JSON coverage report when ``--report`` is given;
prints a one-line summary.
"""
from __future__ import annotations

import json
import os


def add_parser(subparsers):
    parser = subparsers.add_parser("translate", help="translate a Substance .sbs graph into a DiffMat program",
                                   description=__doc__.splitlines()[0])
    parser.add_argument("sbs", metavar="GRAPH.sbs", help="the Substance package to translate")
    parser.add_argument("--out", metavar="DIR", default=".", help="folder for the generated program (default: .)")
    parser.add_argument("--report", metavar="FILE.json", help="write the coverage report (JSON) here")
    parser.add_argument("--graph", metavar="NAME", help="which graph of the package (default: the first material graph)")
    parser.add_argument("--mode", choices=("exposed", "exposed_plus", "all"), default="exposed_plus",
                        help="which parameters are optimisable (default: exposed_plus)")
    parser.set_defaults(run=run)
    return parser


def run(args) -> int:
    from ..translator import translate

    result = translate(args.sbs, args.graph, args.mode)
    report = result.report
    os.makedirs(args.out, exist_ok=True)
    program_path = os.path.join(args.out, f"{report['graph']}.py")
    with open(program_path, "w", encoding="utf-8") as fh:
        fh.write(result.program)
    report = dict(report, program=program_path)
    if args.report:
        folder = os.path.dirname(os.path.abspath(args.report))
        os.makedirs(folder, exist_ok=True)
        with open(args.report, "w", encoding="utf-8") as fh:
            json.dump(report, fh, indent=2, sort_keys=True)
    unsupported = ", ".join(f"{k}×{v}" for k, v in report["unsupported"].items()) or "none"
    print(f"{report['graph']}: {report['nodes_translated']}/{report['nodes_total']} nodes translated, "
          f"{report['nodes_passthrough']} pass-through, {report['nodes_pruned']} pruned, "
          f"{report['params_optimizable']} optimisable parameters ({report['mode']}), "
          f"outputs {', '.join(report['outputs'])}; unsupported: {unsupported}; "
          f"{report['seconds']:.2f} s -> {program_path}")
    return 0
