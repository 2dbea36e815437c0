"""The ``blender-match`` command (also ``python -m blender_match``).

Each sub-command lives in its own module of this package, named after it (``nodes.py`` for
``blender-match nodes``), and defines ``add_parser(subparsers)``, which adds its parser and sets ``run`` with
``parser.set_defaults(run=run)``; ``run(args)`` returns the exit status.
Errors the user can fix (``errors.BlenderMatchError``: a bad option, photo, graph or file) and
file-system errors (``OSError``: a missing file, a full disk) print one line
``blender-match: error: …`` and exit with status 2; a cancelled job (``errors.Cancelled``) prints
``blender-match: cancelled`` and exits with status 130. Anything else is a bug: its traceback is
printed, labelled so, and the status is 1.
"""
from __future__ import annotations

import argparse
import importlib
import pkgutil
import sys
import traceback

from ..allocator import keep_freed_memory
from ..errors import BlenderMatchError, Cancelled

EXIT_ERROR, EXIT_BUG, EXIT_CANCELLED = 2, 1, 130


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
    except Cancelled:
        print("blender-match: cancelled", file=sys.stderr)
        return EXIT_CANCELLED
    except (BlenderMatchError, OSError) as exc:
        print(f"blender-match: error: {exc}", file=sys.stderr)
        return EXIT_ERROR
    except Exception:  # noqa: BLE001 - a bug: show where, and say it is one
        traceback.print_exc()
        print("blender-match: internal error (a bug in blender-match; the traceback above says where)",
              file=sys.stderr)
        return EXIT_BUG


if __name__ == "__main__":
    sys.exit(main())
