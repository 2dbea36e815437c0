"""The two files every benchmark writes into its ``--out`` folder: results.json and results.md."""
from __future__ import annotations

from pathlib import Path

from ..safe_files import write_atomic, write_json_atomic


def write_json_and_markdown(out: Path, payload: dict, markdown: str, default=None):
    """``out``/results.json (``payload``; ``default`` as ``json.dumps`` takes it) and
    ``out``/results.md (``markdown``), each written atomically, replacing an earlier run's."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    write_json_atomic(out / "results.json", payload, overwrite=True, default=default)
    write_atomic(out / "results.md", (markdown.rstrip("\n") + "\n").encode("utf-8"), overwrite=True)
