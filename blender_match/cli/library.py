"""``blender-match library``: the material library, the shipped graphs and the user's own.

``library`` (or ``library list``) lists every graph, ``--json`` as {name, library, file, nodes,
params_optimizable, exposed}; ``--sheet FILE.png`` renders every graph under the flash light into
one contact sheet with its name under each render. ``library add PATH.sbs|DIR [--name N]`` adds
.sbs materials to the user library (``pipeline.user_library``: translation, thumbnail, sample
bank), one summary line per file, a refused file named with its reason; ``library remove NAME``
takes a user graph out.
"""
from __future__ import annotations

import io
import json
import math
from pathlib import Path

import numpy as np
import torch
from PIL import Image, ImageDraw, ImageFont

from ..diffmat.functional.common import check_size
from ..diffmat.render import render_maps
from ..errors import BlenderMatchError, OptionError
from ..library import library_entry, library_names, load_library_graph, user_library_dir
from ..library.catalog import USER_LIBRARY_ENV, by_family, family_of
from ..library.user import remove_entry
from ..pipeline import resolve_device
from ..pipeline.user_library import add_sbs, sbs_files
from ..safe_files import write_atomic
from ._progress import progress_bar

LABEL_HEIGHT = 18
COLUMNS = 8


def _listing_options(p):
    p.add_argument("--json", action="store_true", help="print the graphs as JSON")
    p.add_argument("--sheet", type=Path, metavar="FILE.png", help="write a contact sheet of every graph")
    p.add_argument("--size", type=int, default=256, help="render size of each graph on the sheet (power of two)")
    p.add_argument("--seed", type=int, default=0, help="graph random seed")
    p.add_argument("--overwrite", action="store_true", help="replace an existing sheet")


def add_parser(sub):
    p = sub.add_parser("library", help="list the material library, add your own .sbs materials to it, remove them")
    _listing_options(p)
    p.set_defaults(run=run)
    actions = p.add_subparsers(dest="action", metavar="ACTION")
    listing = actions.add_parser("list", help="list the graphs (the default action)")
    _listing_options(listing)
    add = actions.add_parser("add", help=f"add .sbs materials to the user library (${USER_LIBRARY_ENV}, "
                                         "default: the user-data folder)")
    add.add_argument("paths", nargs="+", type=Path, metavar="PATH.sbs|DIR", help="files, or folders searched for .sbs")
    add.add_argument("--name", help="library name (one file only; default: the file name in lower case)")
    add.add_argument("--graph", dest="graph_name", metavar="ID", help="the graph of the package to add (one file "
                     "only; default: its material graph)")
    add.add_argument("--overwrite", action="store_true", help="replace a user graph of the same name")
    add.add_argument("--device", default="cpu", help="where the bank is rendered: cpu, cuda, mps or auto")
    add.set_defaults(run=run_add)
    remove = actions.add_parser("remove", help="remove graphs from the user library")
    remove.add_argument("names", nargs="+", metavar="NAME")
    remove.set_defaults(run=run_remove)


def entries() -> list[dict]:
    out = []
    for name in library_names():
        e = library_entry(name)
        out.append({"name": e["name"], "library": e["library"], "family": family_of(e), "file": e["path"],
                    "nodes": e["nodes"],
                    "params_optimizable": e["params_optimizable"], "exposed": e["exposed"]})
    return out


def contact_sheet(names: list[str], size: int = 256, seed: int = 0):
    """A PIL image: each graph rendered under the flash, its name below, in rows of COLUMNS, in the
    order given (the command groups them by family)."""

    cols = min(COLUMNS, max(1, len(names)))
    rows = max(1, math.ceil(len(names) / cols))
    sheet = Image.new("RGB", (cols * size, rows * (size + LABEL_HEIGHT)), (24, 24, 24))
    draw = ImageDraw.Draw(sheet)
    font = ImageFont.load_default()
    for i, name in enumerate(names):
        graph = load_library_graph(name)
        with torch.no_grad():
            img = render_maps(graph(size=size, seed=seed))[0]
        arr = (img.clamp(0, 1).permute(1, 2, 0).numpy() * 255 + 0.5).astype(np.uint8)
        x, y = (i % cols) * size, (i // cols) * (size + LABEL_HEIGHT)
        sheet.paste(Image.fromarray(arr), (x, y))
        draw.text((x + 4, y + size + 3), name, fill=(235, 235, 235), font=font)
    return sheet


def run(args) -> int:
    if args.sheet is None and not args.json:
        listed = entries()
        width = max((len(e["name"]) for e in listed), default=0) + 2
        for e in listed:
            print(f"{e['name']:<{width}}{e['library']:<10}{e['family'] or '-':<9}nodes {e['nodes']:>4}  "
                  f"params {e['params_optimizable']:>4}  exposed {', '.join(e['exposed'])}")
        return 0
    if args.json:
        print(json.dumps(entries(), indent=1))
    if args.sheet is not None:
        if args.sheet.exists() and not args.overwrite:
            raise FileExistsError(f"{args.sheet}: already exists (use --overwrite to replace it)")
        check_size(args.size, "--size")
        names = by_family(library_names())
        if not names:
            raise OptionError("library: no library graphs are built (python -m blender_match.library.build)")
        buf = io.BytesIO()
        contact_sheet(names, args.size, args.seed).save(buf, format="PNG")
        write_atomic(args.sheet, buf.getvalue(), overwrite=args.overwrite)
        if not args.json:
            print(f"sheet {args.sheet} ({len(names)} graphs)")
    return 0


def run_add(args) -> int:
    files = [f for path in args.paths for f in sbs_files(path)]
    if not files:
        raise OptionError(f"library add: no .sbs file in {', '.join(map(str, args.paths))}")
    if (args.name or args.graph_name) and len(files) > 1:
        raise OptionError("library add: --name and --graph need a single .sbs file")
    device = resolve_device(args.device)
    print(f"user library: {user_library_dir()}")
    refused = 0
    for index, sbs in enumerate(files, 1):
        bar = progress_bar(0, f"[{index}/{len(files)}] {sbs.name}")

        def progress(done, total, bar=bar):
            bar.total = total
            bar.update(done - bar.n)

        try:
            added = add_sbs(sbs, name=args.name, graph_name=args.graph_name, overwrite=args.overwrite,
                            device=device, progress=progress)
        except BlenderMatchError as exc:
            bar.close()
            print(f"{sbs}: refused: {exc}", flush=True)
            refused += 1
            continue
        bar.close()
        approx = f", {added['passthrough']} node(s) passed through" if added["passthrough"] else ""
        finer = (f", seen from {added['supersample']}x finer renders: its look depends on its output size"
                 if added["supersample"] > 1 else "")
        print(f"{added['name']}: {added['status']} ({added['nodes']} nodes, {added['params']} params{approx}{finer}) "
              f"in {added['seconds']:.1f}s", flush=True)
    print(f"library add: {len(files) - refused} of {len(files)} file(s) in the user library")
    return 2 if refused else 0


def run_remove(args) -> int:
    for name in args.names:
        remove_entry(name)
        print(f"{name}: removed from {user_library_dir()}")
    return 0
