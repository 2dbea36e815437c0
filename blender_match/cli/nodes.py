"""``blender-match nodes``: list the implemented nodes (name, kind, inputs, outputs, parameters
with range, default and whether optimisable), or measure their coverage of real materials.

``--coverage`` reads a node-usage table (Markdown, as in ``shared/reference/node_usage.md``: rows
``| name | uses | materials | …``) and prints the share of the library-node uses that the
implemented nodes cover, and the same for atomic filters.
"""
from __future__ import annotations

import json
import re
from pathlib import Path

from ..diffmat.nodes import all_names, all_specs
from ..errors import OptionError

_ROW = re.compile(r"^\|\s*([A-Za-z0-9_\-]+)\s*\|\s*(\d+)\s*\|")
DEFAULT_USAGE = Path(__file__).resolve().parents[2].parent / "shared" / "reference" / "node_usage.md"


def add_parser(sub):
    p = sub.add_parser("nodes", help="list implemented nodes (--json) or their coverage (--coverage)")
    p.add_argument("--json", action="store_true", help="print every node as JSON")
    p.add_argument("--coverage", action="store_true", help="print the share of real node uses covered")
    p.add_argument("--usage", type=Path, default=DEFAULT_USAGE, help="node-usage table (Markdown)")
    p.set_defaults(run=run)


def read_usage(path: Path) -> dict[str, dict[str, int]]:
    """{"atomic": {name: uses}, "library": {name: uses}} from a node-usage Markdown table."""
    if not path.is_file():
        raise FileNotFoundError(f"{path}: node-usage table not found (pass --usage FILE)")
    tables: dict[str, dict[str, int]] = {"atomic": {}, "library": {}}
    section = None
    for line in path.read_text(encoding="utf-8").splitlines():
        if line.startswith("## "):
            section = "atomic" if "Atomic" in line else "library" if "Library" in line else None
            continue
        match = _ROW.match(line)
        if section and match:
            tables[section][match.group(1)] = int(match.group(2))
    if not tables["library"]:
        raise OptionError(f"{path}: no library-node usage rows found")
    return tables


def coverage(usage: dict[str, int], implemented: set[str]) -> tuple[float, list[str]]:
    """(share of uses whose node is implemented, missing names by uses)."""
    total = sum(usage.values())
    covered = sum(n for name, n in usage.items() if name in implemented)
    missing = sorted((name for name in usage if name not in implemented), key=lambda k: -usage[k])
    return (covered / total if total else 0.0), missing


def run(args) -> int:
    if args.coverage:
        tables = read_usage(args.usage)
        names = all_names()
        for section, label in (("atomic", "atomic filter"), ("library", "library node")):
            share, missing = coverage(tables[section], names)
            uses = sum(tables[section].values())
            print(f"{label} uses covered: {share:.1%} of {uses} "
                  f"({len(tables[section]) - len(missing)}/{len(tables[section])} names); "
                  f"missing most used: {', '.join(missing[:8]) or 'none'}")
        return 0
    specs = all_specs()
    if args.json:
        print(json.dumps([s.describe() for s in specs], indent=1))
        return 0
    for s in specs:
        optimizable = sum(1 for p in s.params if p.continuous and p.optimizable)
        print(f"{s.name:<48} {s.kind:<11} {len(s.params):>3} params ({optimizable} optimisable)")
    return 0
