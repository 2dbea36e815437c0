"""``blender-match translate GRAPH.sbs``: translate a Substance graph into a DiffMat program.

Writes ``<graph>.py`` (a module whose ``build()`` rebuilds the graph with DiffMat calls) into
``--out`` (default: the current directory), and a JSON coverage report when ``--report`` is given;
prints a one-line summary. Files are written atomically; existing ones are kept unless
``--overwrite``.
"""
from __future__ import annotations

from pathlib import Path

from ..safe_files import write_atomic, write_json_atomic
from ..translator import translate


def add_parser(subparsers):
    parser = subparsers.add_parser("translate", help="translate a Substance .sbs graph into a DiffMat program",
                                   description=__doc__.splitlines()[0])
    parser.add_argument("sbs", metavar="GRAPH.sbs", help="the Substance package to translate")
    parser.add_argument("--out", metavar="DIR", default=".", help="folder for the generated program (default: .)")
    parser.add_argument("--report", metavar="FILE.json", help="write the coverage report (JSON) here")
    parser.add_argument("--graph", metavar="NAME",
                        help="which graph of the package (default: the first material graph)")
    parser.add_argument("--mode", choices=("exposed", "exposed_plus", "all"), default="exposed_plus",
                        help="which parameters are optimisable (default: exposed_plus)")
    parser.add_argument("--overwrite", action="store_true", help="replace an existing program or report")
    parser.set_defaults(run=run)
    return parser


def run(args) -> int:
    result = translate(args.sbs, args.graph, args.mode)
    report = result.report
    program_path = Path(args.out) / f"{report['graph']}.py"
    report_path = Path(args.report) if args.report else None
    if not args.overwrite:
        for target in filter(None, (program_path, report_path)):
            if target.exists():
                raise FileExistsError(f"{target}: already exists (use --overwrite to replace it)")
    write_atomic(program_path, result.program.encode("utf-8"), overwrite=True)
    report = dict(report, program=str(program_path))
    if report_path:
        write_json_atomic(report_path, report, overwrite=True)
    unsupported = ", ".join(f"{k}×{v}" for k, v in report["unsupported"].items()) or "none"
    print(f"{report['graph']}: {report['nodes_translated']}/{report['nodes_total']} nodes translated, "
          f"{report['nodes_passthrough']} pass-through, {report['nodes_pruned']} pruned, "
          f"{report['params_optimizable']} optimisable parameters ({report['mode']}), "
          f"outputs {', '.join(report['outputs'])}; unsupported: {unsupported}; "
          f"{report['seconds']:.2f} s -> {program_path}")
    return 0
