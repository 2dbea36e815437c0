"""The two files every benchmark writes into its ``--out`` folder: results.json and results.md."""
from __future__ import annotations

import json
from pathlib import Path

from ..safe_files import write_atomic


def write_json_and_markdown(out: Path, payload: dict, markdown: str, default=None):
    """``out``/results.json (``payload``; ``default`` as ``json.dumps`` takes it) and
    ``out``/results.md (``markdown``), each written atomically, replacing an earlier run's."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    write_atomic(out / "results.json", (json.dumps(payload, indent=1, default=default) + "\n").encode("utf-8"),
                 overwrite=True)
    write_atomic(out / "results.md", (markdown.rstrip("\n") + "\n").encode("utf-8"), overwrite=True)
