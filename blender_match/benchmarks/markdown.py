"""Markdown tables for the benchmarks' results.md files."""
from __future__ import annotations

import math


def cell(value, fmt: str | None = None) -> str:
    """One table cell: floats with ``fmt`` (default 4 significant digits), lists joined, pipes
    escaped, None as a dash."""
    if value is None:
        return "–"
    if isinstance(value, float):
        return format(value, fmt or ".4g") if math.isfinite(value) else str(value)
    if isinstance(value, (list, tuple)):
        return ", ".join(str(v) for v in value)
    return str(value).replace("|", "\\|")


def table(rows: list[dict], columns) -> str:
    """A Markdown table of ``rows``; ``columns``: keys, or (key, title, format) triples."""
    columns = [c if isinstance(c, tuple) else (c, c, None) for c in columns]
    lines = ["| " + " | ".join(title for _, title, _ in columns) + " |",
             "|" + "|".join("---" for _ in columns) + "|"]
    lines.extend("| " + " | ".join(cell(row.get(key), fmt) for key, _, fmt in columns) + " |" for row in rows)
    return "\n".join(lines)
