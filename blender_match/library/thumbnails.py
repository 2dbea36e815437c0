"""Thumbnails of the library graphs for the add-on's graph menu: ``graphs/<name>.png``.

Each library graph is evaluated with its default parameters at ``size`` pixels (128 by default)
and rendered under the flash, as the photos it matches are taken, into ``graphs/<name>.png`` next
to its ``.sbs`` and ``.json`` (the files are shipped with the package; the add-on only reads them,
Blender's Python has no torch)::

    python -m blender_match.library.thumbnails [--overwrite] [NAME ...]

Run it again, with ``--overwrite``, after changing a library graph.
"""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

import torch

from ..diffmat.render import render_maps
from ..errors import OptionError
from ..image_files import write_png
from . import GRAPHS_DIR, builtin_names, load_library_graph

THUMBNAIL_SIZE = 128


def thumbnail_path(name: str, out_dir: Path = GRAPHS_DIR) -> Path:
    return Path(out_dir) / f"{name}.png"


def render_thumbnail(name: str, size: int = THUMBNAIL_SIZE, seed: int = 0):
    """The (1, 3, size, size) sRGB flash render of library graph ``name`` at its defaults."""
    return flash_render(load_library_graph(name), size, seed).clamp(0, 1)


def flash_render(graph, size: int = THUMBNAIL_SIZE, seed: int = 0):
    """The (1, 3, size, size) sRGB flash render of a material graph at its current parameters, on
    the CPU and not clamped (so that a caller can see values that are not finite)."""
    with torch.no_grad():
        maps = graph(size=size, seed=seed)
        return render_maps({usage: m.float().cpu() for usage, m in maps.items()})


def write_thumbnails(names=None, size: int = THUMBNAIL_SIZE, out_dir: Path = GRAPHS_DIR,
                     overwrite: bool = False) -> list[Path]:
    """Write ``<out_dir>/<name>.png`` for each library graph (all by default); their paths.
    Existing thumbnails are kept unless ``overwrite``."""
    names = builtin_names() if names is None else list(names)
    unknown = sorted(set(names) - set(builtin_names()))
    if unknown:
        raise OptionError(f"not library graphs: {', '.join(unknown)} (library: {', '.join(builtin_names())})")
    written = []
    for name in names:
        path = thumbnail_path(name, out_dir)
        if path.exists() and not overwrite:
            continue
        write_png(path, render_thumbnail(name, size), overwrite=overwrite)
        written.append(path)
    return written


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(prog="python -m blender_match.library.thumbnails",
                                     description="render the library graphs' thumbnails for the add-on")
    parser.add_argument("names", nargs="*", help="library graphs (default: all)")
    parser.add_argument("--size", type=int, default=THUMBNAIL_SIZE, help="thumbnail size in pixels")
    parser.add_argument("--overwrite", action="store_true", help="replace existing thumbnails")
    args = parser.parse_args(argv)
    for path in write_thumbnails(args.names or None, args.size, overwrite=args.overwrite):
        print(path)
    return 0


if __name__ == "__main__":
    sys.exit(main())
