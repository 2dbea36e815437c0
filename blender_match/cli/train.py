"""``blender-match train [--graph NAME... | --all]``: train the parameter predictors and build the
sample banks that automatic graph selection (``blender-match match`` without ``--graph``) uses.

Per library graph it writes, in ``blender_match/library/models/``, ``<name>.bank.pt``,
``<name>.predictor.pt`` and ``<name>.predictor.json`` (see ``blender_match.selection``). Graphs
whose files are up to date (same hash of the .sbs and its
``.json`` parameter space) are skipped unless ``--force``; so after adding a
graph to the library, ``blender-match train --all`` trains only that one. ``--resume`` continues
an interrupted training from its checkpoint (``<name>.train.pt``) instead of starting over.
Progress goes to stderr, one summary line per graph to stdout.
"""
from __future__ import annotations

import time
from pathlib import Path

import torch

from ..errors import OptionError
from ..library import library_names
from ..pipeline import resolve_device
from ..selection.bank import BANK_SIZE, bank_is_current
from ..selection.predictor import (
    DEFAULT_EPOCHS,
    DEFAULT_RENDER_STEPS,
    DEFAULT_SAMPLES,
    predictor_is_current,
    train_graph,
)
from ._progress import progress_bar


def add_parser(sub):
    p = sub.add_parser("train", help="train graph-selection models (predictors and sample banks)")
    which = p.add_mutually_exclusive_group(required=True)
    which.add_argument("--graph", nargs="+", metavar="NAME", help="library graphs to train")
    which.add_argument("--all", action="store_true", help="every library graph (up-to-date ones are skipped)")
    p.add_argument("--samples", type=int, default=DEFAULT_SAMPLES,
                   help=f"synthetic examples rendered per graph, bank included (default {DEFAULT_SAMPLES})")
    p.add_argument("--epochs", type=int, default=DEFAULT_EPOCHS,
                   help=f"epochs of the parameter loss (default {DEFAULT_EPOCHS})")
    p.add_argument("--render-steps", type=int, default=DEFAULT_RENDER_STEPS,
                   help=f"steps of the rendering-loss phase (default {DEFAULT_RENDER_STEPS})")
    p.add_argument("--bank", type=int, default=BANK_SIZE, help=f"samples in the bank (default {BANK_SIZE})")
    p.add_argument("--resume", action="store_true", help="continue from a checkpoint left by an interrupted run")
    p.add_argument("--keep-data", action="store_true",
                   help="keep the rendered examples (<name>.train.pt) after training, for --resume --force")
    p.add_argument("--force", action="store_true", help="retrain graphs whose models are up to date")
    p.add_argument("--models", type=Path, help="models folder (default: the library's)")
    p.add_argument("--device", default="cpu", help="cpu, cuda or mps (default cpu)")
    p.add_argument("--threads", type=int, default=0, help="CPU threads for torch (0: torch's default)")
    p.set_defaults(run=run)


class _TrainingProgress:
    """A bar per phase of a graph's training (data, fit, render): steps done of the phase's
    total, with the validation error while fitting."""

    def __init__(self, label: str):
        self.label, self.phase = label, None
        self.bar = progress_bar(0, label)

    def __call__(self, event: dict):
        if event["phase"] != self.phase:
            self.phase = event["phase"]
            self.bar.set_description_str(f"{self.label} {self.phase}", refresh=False)
            self.bar.set_postfix_str("", refresh=False)
            self.bar.reset(total=event["total"])
        if "val_error" in event:
            self.bar.set_postfix_str(f"val error {event['val_error']:.4f}", refresh=False)
        self.bar.update(event["done"] - self.bar.n)

    def close(self):
        self.bar.close()


def run(args) -> int:
    if args.threads:
        torch.set_num_threads(args.threads)
    names = library_names() if args.all else args.graph
    unknown = [n for n in names if n not in library_names()]
    if unknown:
        raise OptionError(f"train: {unknown[0]} is not a library graph ({', '.join(library_names())})")
    if args.samples < 1 or args.epochs < 1 or args.render_steps < 0 or args.bank < 1:
        raise OptionError("train: --samples, --epochs and --bank must be positive, --render-steps non-negative")
    device = resolve_device(args.device)
    total = time.perf_counter()
    for name in names:
        if not args.force and predictor_is_current(name, args.models) and bank_is_current(name, args.models):
            print(f"{name}: up to date (skipped)")
            continue
        bar = _TrainingProgress(name)
        try:
            meta = train_graph(name, samples=args.samples, epochs=args.epochs, render_steps=args.render_steps,
                               bank_size=args.bank, directory=args.models, resume=args.resume, device=device,
                               progress=bar, keep_data=args.keep_data)
        finally:
            bar.close()
        s = meta["seconds"]
        print(f"{name}: {meta['params']} params ({meta['sampled_params']} sampled), "
              f"{meta['training_samples']}+{meta['validation_samples']} examples, "
              f"val error {meta['val_param_error']:.4f} (default {meta['val_param_error_default']:.4f}), "
              f"data {s['data']:.0f}s fit {s['fit']:.0f}s render {s['render']:.0f}s, wall {meta['wall_seconds']:.0f}s",
              flush=True)
    print(f"train: {len(names)} graph(s) in {time.perf_counter() - total:.0f}s")
    return 0
