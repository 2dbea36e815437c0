"""``blender-match match PHOTO --graph NAME --out DIR``: fit a procedural material to a photo and
write its tiling maps, parameters, a comparison image and ``report.json`` (``pipeline.match_photo``).
"""
from __future__ import annotations

import argparse
import json
from pathlib import Path

from ..pipeline import AUTO_CANDIDATES, MatchOptions, match_photo
from ..vocabulary import DEFAULT_DEVICE, DEFAULT_QUALITY, DEVICE_NAMES, QUALITY_NAMES, ranked_alternatives
from ._progress import progress_bar


def add_parser(sub):
    p = sub.add_parser("match", help="fit a graph to a photo and write its maps")
    p.add_argument("photo", type=Path, help="photo of a flat material sample (JPEG, PNG, TIFF, EXR...)")
    p.add_argument("--graph", help="library or bundled graph name, or a .sbs file")
    p.add_argument("--out", type=Path, required=True, help="output folder")
    p.add_argument("--size", type=int, default=2048, help="size of the maps written (default 2048)")
    p.add_argument("--quality", choices=QUALITY_NAMES, default=DEFAULT_QUALITY, help="time against accuracy")
    p.add_argument("--seed", type=int, default=0, help="graph random seed (same seed, same maps)")
    p.add_argument("--device", choices=DEVICE_NAMES, default=DEFAULT_DEVICE,
                   help=f"where to run (default {DEFAULT_DEVICE})")
    p.add_argument("--iterations", type=int, help="override the quality preset's iteration count")
    p.add_argument("--candidates", type=int, default=AUTO_CANDIDATES,
                   help=f"without --graph: fit this many of the best-ranked graphs and keep the best fit "
                        f"(default {AUTO_CANDIDATES}; 3 is the MATch paper's)")
    p.add_argument("--no-calibration", dest="calibrate", action="store_false",
                   help="keep the base colour as the graph gives it (default: scale it to the photo's "
                        "exposure and white balance at the fit's start and after it)")
    p.add_argument("--zoom", type=zoom_argument, default=1.0, metavar="auto|Z",
                   help="texture periods across the photo (default 1: the graph's own scale; auto: searched "
                        "over 1, 2 and 4); the Blender material carries it as its Mapping scale")
    p.add_argument("--no-lighting", dest="lighting", action="store_false",
                   help="fit under the ideal flash (default: under the photo's flash falloff and vignetting, "
                        "solved from the photo; the maps never carry it)")
    p.add_argument("--overwrite", action="store_true", help="replace files already in --out")
    p.add_argument("--json", action="store_true", help="print the report as JSON instead of a summary")
    p.set_defaults(run=run)


def zoom_argument(text: str) -> float | None:
    """``--zoom``: "auto" (None: searched) or a number (checked against the range by the pipeline)."""
    if text == "auto":
        return None
    try:
        return float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected auto or a number, not {text!r}") from None


class _MatchProgress:
    """The job's progress as a bar: the stage, the share of the whole job done, and while fitting
    the iteration and the loss, then the time the pipeline expects the job still needs."""

    def __init__(self):
        self.bar = progress_bar(100, bar_format="{desc:<13} {percentage:5.1f}%|{bar}| [{elapsed}{postfix}]")

    def __call__(self, event: dict):
        details = []
        if "loss" in event:
            details.append(f"iteration {event['iteration']}/{event['iterations']}  loss {event['loss']:.5f}")
        if event.get("eta_seconds") is not None:
            details.append(f"{event['eta_seconds']:.0f} s left")
        self.bar.set_description_str(event["stage"], refresh=False)
        self.bar.set_postfix_str("  ".join(details), refresh=False)
        self.bar.update(100 * event["fraction"] - self.bar.n)

    def close(self):
        self.bar.close()


def run(args) -> int:
    options = MatchOptions(graph=args.graph, size=args.size, quality=args.quality, seed=args.seed,
                           device=args.device, overwrite=args.overwrite, iterations=args.iterations,
                           candidates=args.candidates, calibrate=args.calibrate, zoom=args.zoom,
                           lighting=args.lighting)
    display = _MatchProgress()
    try:
        report = match_photo(args.photo, args.out, options, progress=display)
    finally:
        display.close()
    if args.json:
        print(json.dumps(report, indent=1))
    else:
        print_summary(report, args.out)
    return 0


def print_summary(report: dict, out: Path) -> None:
    """The match's summary lines: graph, loss, iterations and time; an automatic match's next-ranked
    graphs; the zoom; each map's file; the report's."""
    print(f"graph {report['graph']}: loss {report['loss_initial']:.5f} -> {report['loss_final']:.5f} "
          f"in {report['iterations']} iterations, {report['seconds']:.1f} s on {report['device']}")
    alternatives = ranked_alternatives(report)
    if alternatives:
        print(f"also close       {', '.join(alternatives)} (ranked next: --graph NAME matches one of them)")
    zoom = report.get("calibration", {}).get("zoom", 1.0)
    if zoom != 1:
        print(f"zoom             {zoom:g} texture periods across the photo (the material's Mapping scale)")
    for usage, info in report["maps"].items():
        flat = f" (flat: {info['flat']})" if info["flat"] else ""
        print(f"{usage:<17} {out / info['file']}{flat}")
    print(f"report           {out / 'report.json'}")
