"""Shared fixtures and checks for the test suite."""
from __future__ import annotations

import atexit
import os
import shutil
import tempfile
from pathlib import Path

import pytest
import torch

from blender_match.allocator import keep_freed_memory
from blender_match.library.catalog import USER_LIBRARY_ENV

keep_freed_memory()  # as the command line and the worker do: the suite runs faster
# the suite sees an empty user library of its own (subprocesses inherit it), never the developer's
os.environ[USER_LIBRARY_ENV] = tempfile.mkdtemp(prefix="blender-match-user-library-")
atexit.register(shutil.rmtree, os.environ[USER_LIBRARY_ENV], ignore_errors=True)  # gone when the run ends
ROOT = Path(__file__).resolve().parents[1]
SHARED = Path(os.environ.get("BLENDER_MATCH_SHARED", ROOT.parent / "shared"))


def pytest_collection_modifyitems(items):
    """Marks each test by what it needs, so a run can choose (``-m "not slow"``, ``-m bpy``):
    ``bpy`` for the add-on's tests (``tests/addon/``; elsewhere a test that runs Blender's module in
    a subprocess says so itself), ``shared`` where it reads ``../shared`` (the ``shared_dir``
    fixture or ``SHARED``). ``slow`` is set by hand on the tests themselves."""
    addon = ROOT / "tests" / "addon"
    for item in items:
        module = getattr(item, "module", None)
        names = vars(module) if module is not None else {}
        if addon in Path(str(item.fspath)).parents:
            item.add_marker(pytest.mark.bpy)
        if "shared_dir" in getattr(item, "fixturenames", ()) or names.get("SHARED") is SHARED:
            item.add_marker(pytest.mark.shared)


@pytest.fixture(autouse=True)
def _deterministic():
    torch.manual_seed(0)
    yield


@pytest.fixture(scope="session")
def shared_dir() -> Path:
    if not SHARED.is_dir():
        pytest.fail(f"../shared not found at {SHARED}: the tests read real data from it")
    return SHARED


@pytest.fixture(scope="session")
def plaster_photo(shared_dir: Path) -> Path:
    """The real flash photo of a plaster wall that the Blender sessions match."""
    photo = shared_dir / "data" / "photos" / "real_plaster_wall_beige_desch18.png"
    if not photo.is_file():
        pytest.fail(f"{photo}: the shared test photo is missing")
    return photo
