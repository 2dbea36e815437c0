"""``blender-match library``: the shipped material library (``blender_match/library``).

``--json`` lists every graph ({name, file, nodes, params_optimizable, exposed}); ``--sheet FILE.png``
renders every graph under the flash light into one contact sheet with its name under each render.
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
from ..errors import OptionError
from ..library import library_entry, library_names, load_library_graph
from ..safe_files import write_atomic

LABEL_HEIGHT = 18
COLUMNS = 4


def add_parser(sub):
    p = sub.add_parser("library", help="list the material library or render its contact sheet")
    p.add_argument("--json", action="store_true", help="print the graphs as JSON")
    p.add_argument("--sheet", type=Path, metavar="FILE.png", help="write a contact sheet of every graph")
    p.add_argument("--size", type=int, default=256, help="render size of each graph on the sheet (power of two)")
    p.add_argument("--seed", type=int, default=0, help="graph random seed")
    p.add_argument("--overwrite", action="store_true", help="replace an existing sheet")
    p.set_defaults(run=run)


def entries() -> list[dict]:
    out = []
    for name in library_names():
        e = library_entry(name)
        out.append({"name": e["name"], "file": e["path"], "nodes": e["nodes"],
                    "params_optimizable": e["params_optimizable"], "exposed": e["exposed"]})
    return out


def contact_sheet(names: list[str], size: int = 256, seed: int = 0):
    """A PIL image: each graph rendered under the flash, its name below, in rows of COLUMNS."""

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
        for e in entries():
            print(f"{e['name']:<18} nodes {e['nodes']:>4}  params {e['params_optimizable']:>4}  "
                  f"exposed {', '.join(e['exposed'])}")
        return 0
    if args.json:
        print(json.dumps(entries(), indent=1))
    if args.sheet is not None:
        if args.sheet.exists() and not args.overwrite:
            raise FileExistsError(f"{args.sheet}: already exists (use --overwrite to replace it)")
        check_size(args.size, "--size")
        names = library_names()
        if not names:
            raise OptionError("library: no library graphs are built (python -m blender_match.library.build)")
        buf = io.BytesIO()
        contact_sheet(names, args.size, args.seed).save(buf, format="PNG")
        write_atomic(args.sheet, buf.getvalue(), overwrite=args.overwrite)
        if not args.json:
            print(f"sheet {args.sheet} ({len(names)} graphs)")
    return 0
