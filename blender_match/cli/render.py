"""``blender-match render SOURCE``: evaluate a material graph and write its maps, plus
``render.png``, the material under the flash light.

SOURCE is a bundled graph's name (``blender-match render --list``) or a Substance ``.sbs`` file.
"""
from __future__ import annotations

import json
import time
from pathlib import Path


def add_parser(sub):
    p = sub.add_parser("render", help="render a graph's maps (bundled name or .sbs file)")
    p.add_argument("source", nargs="?", help="bundled graph name or path to a .sbs file")
    p.add_argument("--size", type=int, default=512, help="output size in pixels (power of two)")
    p.add_argument("--seed", type=int, default=0, help="graph random seed")
    p.add_argument("--out", type=Path, help="output folder")
    p.add_argument("--overwrite", action="store_true", help="replace existing map files")
    p.add_argument("--list", action="store_true", help="list the bundled graphs")
    p.set_defaults(run=run)


def load_graph(source: str):
    """A MaterialGraph from a bundled name or an .sbs path."""
    from ..bundled_graphs import BUNDLED, build

    if source in BUNDLED:
        return build(source)
    path = Path(source)
    if path.suffix.lower() == ".sbs":
        from ..translator import load_sbs_graph

        return load_sbs_graph(path)
    raise ValueError(f"{source}: not a bundled graph ({', '.join(sorted(BUNDLED))}) nor a .sbs file")


def run(args) -> int:
    from ..bundled_graphs import BUNDLED

    if args.list:
        for name, (_, doc) in sorted(BUNDLED.items()):
            print(f"{name:<20} {doc}")
        return 0
    if not args.source or not args.out:
        raise ValueError("render: give a SOURCE and --out DIR (or --list)")
    import torch

    from ..diffmat.render import render_maps
    from ..image_files import write_png
    from ..material_maps import write_maps

    render_path = args.out / "render.png"
    if render_path.exists() and not args.overwrite:
        raise FileExistsError(f"{render_path}: already exists (use --overwrite to replace it)")
    graph = load_graph(args.source)
    start = time.perf_counter()
    with torch.no_grad():
        maps = graph(size=args.size, seed=args.seed)
    seconds = time.perf_counter() - start
    written = write_maps(maps, args.out, overwrite=args.overwrite)
    if "basecolor" in maps:
        with torch.no_grad():
            write_png(render_path, render_maps(maps), overwrite=True)
    for usage, info in written.items():
        flat = f" (flat: {info['flat']})" if info["flat"] else ""
        print(f"{usage:<17} {args.out / info['file']}{flat}")
    print(json.dumps({"graph": graph.name, "size": args.size, "seed": args.seed, "seconds": round(seconds, 3)}))
    return 0
