"""Running a script in a fresh Python with Blender's bpy module, the way the add-on tests see
Blender: the script prints one line ``RESULT <json>``, which this returns as a dict."""
from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path


def run_blender_script(script: str, args: list[str], work: Path, env: dict, timeout: int) -> dict:
    result = subprocess.run([sys.executable, "-c", script, *args], cwd=work, env=env, capture_output=True,
                            text=True, timeout=timeout)
    assert result.returncode == 0, result.stdout[-3000:] + result.stderr[-5000:]
    [line] = [line for line in result.stdout.splitlines() if line.startswith("RESULT ")]
    out = json.loads(line[len("RESULT "):])
    print("session steps (seconds since start):", out["seconds"])
    return out
