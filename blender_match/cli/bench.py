"""``blender-match bench [WHAT]``: run benchmarks and print their figures as a table."""
from __future__ import annotations

import argparse
import importlib
import inspect
import json
from pathlib import Path

import torch

from ..errors import OptionError
from .match import zoom_argument

SUITES = ("nodes", "translator", "library", "match", "accuracy", "selection", "recovery", "photos", "ranking")
# the suite options, by the keyword a suite's ``run`` takes each as (the rest go to every suite)
OPTION_FLAGS = {"files": "--files", "graphs": "--graphs", "paper_iterations": "--paper-iterations",
                "quality": "--quality", "quick": "--quick", "photos": "--photos", "iterations": "--iterations",
                "candidates": "--candidates", "zoom": "--zoom", "lighting": "--no-lighting", "out": "--out"}


def add_parser(sub):
    # a suite option (``OPTION_FLAGS``) is in the parsed arguments only when given: what a suite
    # is passed is what the user asked for, and its own defaults stand for the rest
    p = sub.add_parser("bench", help="run benchmarks and print figures", argument_default=argparse.SUPPRESS)
    p.add_argument("what", nargs="?", choices=SUITES, default=None,
                   help="which benchmark (default: accuracy with --out, else nodes)")
    p.add_argument("--device", default="cpu", help="cpu, cuda or mps")
    p.add_argument("--threads", type=int, default=0, help="CPU threads for torch (0: torch's default)")
    p.add_argument("--files", nargs="+", type=Path, help="input files, for suites that take them (translator)")
    p.add_argument("--graphs", nargs="+", help="library graphs to use (match, accuracy)")
    p.add_argument("--paper-iterations", type=int, help="iterations of the paper's optimiser (match)")
    p.add_argument("--quality", help="our preset to compare (match), the preset to use (photos)")
    p.add_argument("--quick", action="store_true",
                   help="a small subset that runs in minutes (accuracy, recovery; photos: the draft preset)")
    p.add_argument("--photos", type=Path,
                   help="folder of photos to match (photos; default ../shared/data/photos_dev) or rank (ranking; "
                   "default: photos_dev and the bundled photos)")
    p.add_argument("--iterations", type=int,
                   help="iterations of each fit, rescaling the quality preset (photos, recovery, selection)")
    p.add_argument("--candidates", type=int,
                   help="graphs automatic matching fits per photo (photos; default: match's default)")
    p.add_argument("--zoom", type=zoom_argument, metavar="auto|Z",
                   help="texture periods across the photo (photos, recovery; default 1; auto: searched)")
    p.add_argument("--no-lighting", dest="lighting", action="store_false",
                   help="fit under the ideal flash, not the photo's solved falloff (photos, recovery)")
    p.add_argument("--out", type=Path,
                   help="folder for results.json, results.md and charts "
                   "(accuracy, recovery, photos, ranking, translator)")
    p.add_argument("--json", action="store_true", default=False, help="print rows as JSON")
    p.set_defaults(run=run)


def suite_options(run_function) -> set[str]:
    """The keyword names of the options a suite's ``run`` takes."""
    return {name for name, p in inspect.signature(run_function).parameters.items()
            if p.kind in (p.POSITIONAL_OR_KEYWORD, p.KEYWORD_ONLY)}


def check_options(what: str, given, taken: set[str]):
    """OptionError naming the options ``given`` (keyword names) that suite ``what`` does not take,
    each of which would otherwise be lost without a word or stop the run with a traceback, and
    the ones it does take."""
    refused = [OPTION_FLAGS[name] for name in given if name not in taken]
    if refused:
        accepted = [flag for name, flag in OPTION_FLAGS.items() if name in taken]
        raise OptionError(f"bench {what} does not take {', '.join(refused)}; it takes "
                          + (", ".join(accepted) if accepted else "none of the suites' options")
                          + " (and --device, --threads, --json)")


def print_table(rows: list[dict]):
    cols = list(rows[0])
    cells = [[f"{r[c]:.3f}" if isinstance(r[c], float) else str(r[c]) for c in cols] for r in rows]
    widths = [max(len(c), *(len(row[i]) for row in cells)) for i, c in enumerate(cols)]
    print(" | ".join(c.ljust(w) for c, w in zip(cols, widths)))
    print("-|-".join("-" * w for w in widths))
    for row in cells:
        print(" | ".join(v.ljust(w) for v, w in zip(row, widths)))


def run(args) -> int:
    if args.threads:
        torch.set_num_threads(args.threads)
    args.what = args.what or ("accuracy" if getattr(args, "out", None) else "nodes")
    # the suite is chosen by name at run time: SUITES are the modules of blender_match.benchmarks
    module = importlib.import_module(f"blender_match.benchmarks.{args.what}")
    extra = {name: getattr(args, name) for name in OPTION_FLAGS if hasattr(args, name)}  # "--zoom auto": None
    check_options(args.what, extra, suite_options(module.run))
    rows = module.run(device=args.device, **extra)
    if args.json:
        print(json.dumps(rows, indent=1))
    else:
        print(f"bench {args.what}: device {args.device}, torch threads {torch.get_num_threads()}")
        if rows:
            print_table(rows)
    return 0
