"""The worker's requirements (``backend_setup.WORKER_REQUIREMENTS``, what the add-on installs into
the backend) are the one list of the engine's dependencies: pyproject.toml must declare the same
ones, plus only what the command line alone uses."""
from __future__ import annotations

import tomllib

from conftest import ROOT

from blender_match.worker.backend_setup import WORKER_IMPORTS, WORKER_REQUIREMENTS, requirement_name

# progress bars of the blender-match command; the worker reports progress as events, not bars
COMMAND_LINE_ONLY = ("tqdm>=4.66",)


def _project_dependencies() -> list[str]:
    with open(ROOT / "pyproject.toml", "rb") as f:
        return tomllib.load(f)["project"]["dependencies"]


def test_pyproject_declares_the_worker_requirements_and_the_command_lines():
    assert sorted(_project_dependencies()) == sorted(WORKER_REQUIREMENTS + COMMAND_LINE_ONLY)


def test_every_worker_requirement_names_the_module_the_worker_checks():
    assert sorted(map(requirement_name, WORKER_REQUIREMENTS)) == sorted(WORKER_IMPORTS)
