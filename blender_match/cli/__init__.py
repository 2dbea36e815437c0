"""The ``blender-match`` command (also ``python -m blender_match``).

Each sub-command lives in its own module of this package, named after it (``nodes.py`` for
``blender-match nodes``), and defines ``add_parser(subparsers)``, which adds its parser and sets ``run`` with
``parser.set_defaults(run=run)``; ``run(args)`` returns the exit status.
Errors the user can fix (DiffMatError, a translator error, a missing file) print one line
``blender-match: error: …`` and exit with status 2.
"""
from __future__ import annotations

import argparse
import importlib
import pkgutil
import sys

from ..allocator import keep_freed_memory


def _commands():
    for info in sorted(pkgutil.iter_modules(__path__), key=lambda m: m.name):
        if not info.name.startswith("_"):
            yield importlib.import_module(f"{__name__}.{info.name}")


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="blender-match", description=__doc__.splitlines()[0])
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    for module in _commands():
        module.add_parser(sub)
    return parser


def main(argv: list[str] | None = None) -> int:
    args = build_parser().parse_args(argv)
    keep_freed_memory()
    try:
        return int(args.run(args) or 0)
    except (ValueError, OSError) as exc:  # DiffMatError and the translator's errors are ValueErrors
        print(f"blender-match: error: {exc}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
