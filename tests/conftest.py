"""Shared fixtures and checks for the test suite."""
from __future__ import annotations

import os
from pathlib import Path

import pytest
import torch

from blender_match.allocator import keep_freed_memory

keep_freed_memory()  # as the command line and the worker do: the suite runs faster
ROOT = Path(__file__).resolve().parents[1]
SHARED = Path(os.environ.get("BLENDER_MATCH_SHARED", ROOT.parent / "shared"))


@pytest.fixture(autouse=True)
def _deterministic():
    torch.manual_seed(0)
    yield


@pytest.fixture
def shared_dir() -> Path:
    if not SHARED.is_dir():
        pytest.fail(f"../shared not found at {SHARED}: the tests read real data from it")
    return SHARED
