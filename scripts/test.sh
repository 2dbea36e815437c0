#!/usr/bin/env bash
# Set up (scripts/setup.sh), check the code (ruff, mypy: configured in pyproject.toml) and run the
# whole test suite. CI runs exactly this (.ci/run). Arguments go to pytest (e.g. -m "not slow").
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
.venv/bin/ruff check --quiet blender_match tests
.venv/bin/mypy
exec .venv/bin/python -m pytest "$@"
