"""``blender-match match PHOTO --graph NAME --out DIR``: fit a procedural material to a photo and
write its tiling maps, parameters, a comparison image and ``report.json`` (``pipeline.match_photo``).
"""
from __future__ import annotations

import json
import sys
import time
from pathlib import Path


def add_parser(sub):
    from ..pipeline import DEVICES, QUALITIES

    p = sub.add_parser("match", help="fit a graph to a photo and write its maps")
    p.add_argument("photo", type=Path, help="photo of a flat material sample (JPEG, PNG, TIFF, EXR...)")
    p.add_argument("--graph", help="library or bundled graph name, or a .sbs file")
    p.add_argument("--out", type=Path, required=True, help="output folder")
    p.add_argument("--size", type=int, default=2048, help="size of the maps written (default 2048)")
    p.add_argument("--quality", choices=QUALITIES, default="balanced", help="time against accuracy")
    p.add_argument("--seed", type=int, default=0, help="graph random seed (same seed, same maps)")
    p.add_argument("--device", choices=DEVICES, default="auto", help="where to run (default auto)")
    p.add_argument("--iterations", type=int, help="override the quality preset's iteration count")
    p.add_argument("--overwrite", action="store_true", help="replace files already in --out")
    p.add_argument("--json", action="store_true", help="print the report as JSON instead of a summary")
    p.set_defaults(run=run)


class _ProgressLine:
    """A one-line progress display on stderr (a TTY), throttled to a few updates per second."""

    def __init__(self):
        self.last = 0.0
        self.tty = sys.stderr.isatty()

    def __call__(self, event: dict):
        now = time.monotonic()
        if not self.tty or (now - self.last < 0.25 and event.get("stage") == "fitting"):
            return
        self.last = now
        text = f"{event['stage']:<13} {100 * event['fraction']:5.1f}%"
        if "loss" in event:
            text += f"  iteration {event['iteration']}/{event['iterations']}  loss {event['loss']:.5f}"
        if event.get("eta_seconds") is not None:
            text += f"  {event['eta_seconds']:.0f} s left"
        sys.stderr.write("\r" + text.ljust(79))
        sys.stderr.flush()

    def close(self):
        if self.tty:
            sys.stderr.write("\n")


def run(args) -> int:
    from ..pipeline import MatchOptions, match_photo

    options = MatchOptions(graph=args.graph, size=args.size, quality=args.quality, seed=args.seed,
                           device=args.device, overwrite=args.overwrite, iterations=args.iterations)
    display = _ProgressLine()
    try:
        report = match_photo(args.photo, args.out, options, progress=display)
    finally:
        display.close()
    if args.json:
        print(json.dumps(report, indent=1))
        return 0
    print(f"graph {report['graph']}: loss {report['loss_initial']:.5f} -> {report['loss_final']:.5f} "
          f"in {report['iterations']} iterations, {report['seconds']:.1f} s on {report['device']}")
    for usage, info in report["maps"].items():
        flat = f" (flat: {info['flat']})" if info["flat"] else ""
        print(f"{usage:<17} {args.out / info['file']}{flat}")
    print(f"report           {args.out / 'report.json'}")
    return 0
