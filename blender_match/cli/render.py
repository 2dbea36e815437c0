"""``blender-match render SOURCE``: evaluate a material graph and write its maps, plus
``render.png``, the material under the flash light.

SOURCE is a bundled graph's name (``blender-match render --list``), a library graph's name
(``blender-match library``) or a Substance ``.sbs`` file. ``--sample K`` (library graphs) renders the
K-th random variant drawn from the graph's declared parameter ranges and writes the parameters it
used to ``params.json`` in the output folder (a parameter file ``--params`` reads back).
"""
from __future__ import annotations

import json
import time
from pathlib import Path

import torch

from ..bundled_graphs import BUNDLED
from ..diffmat.params_file import apply_params, load_params
from ..diffmat.render import render_maps
from ..errors import OptionError
from ..image_files import write_png
from ..library import library_names, sample_params
from ..material_maps import write_maps
from ..pipeline import load_graph
from ..pipeline.result_folder import refuse_existing
from ..safe_files import write_json_atomic
from ..vocabulary import PARAMS_FILE

RENDER_FILE = "render.png"


def add_parser(sub):
    p = sub.add_parser("render", help="render a graph's maps (bundled or library name, or .sbs file)")
    p.add_argument("source", nargs="?", help="bundled or library graph name, or path to a .sbs file")
    p.add_argument("--size", type=int, default=512, help="output size in pixels (power of two)")
    p.add_argument("--seed", type=int, default=0, help="graph random seed")
    p.add_argument("--out", type=Path, help="output folder")
    group = p.add_mutually_exclusive_group()
    group.add_argument("--params", type=Path, help="parameter file (JSON, as written by a match) to apply")
    group.add_argument("--sample", type=int, metavar="K",
                       help="library graphs: render the K-th random variant and write its params.json")
    p.add_argument("--overwrite", action="store_true", help="replace existing map files")
    p.add_argument("--list", action="store_true", help="list the bundled graphs")
    p.set_defaults(run=run)


def run(args) -> int:
    if args.list:
        for name, (_, doc) in sorted(BUNDLED.items()):
            print(f"{name:<20} {doc}")
        return 0
    if not args.source or not args.out:
        raise OptionError("render: give a SOURCE and --out DIR (or --list)")
    render_path = args.out / RENDER_FILE
    refuse_existing([render_path], args.overwrite)
    params_path = args.out / PARAMS_FILE
    if args.sample is not None:
        if args.source not in library_names():
            raise OptionError(f"{args.source}: --sample needs a library graph ({', '.join(library_names())})")
        if args.sample < 0:
            raise OptionError(f"--sample: expected a non-negative integer, got {args.sample}")
        refuse_existing([params_path], args.overwrite)
    graph = load_graph(args.source)
    if args.sample is not None:
        params = sample_params(args.source, args.sample)
        apply_params(graph, params, f"{args.source} sample {args.sample}")
        write_json_atomic(params_path, {"graph": graph.name, "sample": args.sample, "params": params}, args.overwrite)
    if args.params:
        load_params(graph, args.params)
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
