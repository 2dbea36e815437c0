#!/usr/bin/env bash
# Set up the development environment: a Python 3.11 virtual environment in .venv with the
# project installed in editable mode and its test dependencies (torch, bpy 5.0.1, …).
# Idempotent: re-running only installs what pyproject.toml changed.
set -euo pipefail
cd "$(dirname "$0")/.."
PY=${PYTHON:-}
if [[ -z "$PY" ]]; then
  for candidate in python3.11 python3; do
    if command -v "$candidate" >/dev/null && "$candidate" -c 'import sys; sys.exit(sys.version_info[:2] != (3, 11))'; then
      PY=$candidate; break
    fi
  done
fi
if [[ -z "$PY" ]]; then
  echo "setup: Python 3.11 is required (bpy 5.0.1 is built for it); set PYTHON=/path/to/python3.11" >&2
  exit 2
fi
if [[ ! -x .venv/bin/python ]]; then
  "$PY" -m venv .venv
fi
stamp=.venv/.blender_match_installed
want=$(sha256sum pyproject.toml | cut -d' ' -f1)
if [[ ! -f $stamp || $(cat "$stamp") != "$want" ]]; then
  .venv/bin/python -m pip install --quiet --upgrade pip
  .venv/bin/python -m pip install --quiet -e ".[test]"
  echo "$want" > "$stamp"
fi
