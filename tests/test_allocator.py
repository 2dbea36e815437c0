"""The allocator tuning the command line, the worker and the benchmarks apply at start."""
from __future__ import annotations

import subprocess
import sys

import pytest
import torch

from blender_match.allocator import keep_freed_memory
from blender_match.benchmarks.measure import measure


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="glibc only")
def test_glibc_accepts_the_settings():
    assert keep_freed_memory() is True


def test_the_command_line_applies_it():
    code = ("import blender_match.allocator as a, sys\n"
            "calls = []\n"
            "a.keep_freed_memory = lambda: calls.append(1) or True\n"
            "from blender_match.cli import main\n"
            "main(['nodes', '--json'])\n"
            "sys.stderr.write(str(len(calls)))\n")
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0 and proc.stderr.strip().endswith("1")


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="glibc only")
def test_a_measured_peak_is_not_hidden_by_memory_kept_from_an_earlier_run():
    keep_freed_memory()
    blocks = [torch.ones(4, 2**20 // 4) for _ in range(16)]  # 16 x 4 MiB, freed but kept
    del blocks
    with measure() as m:
        again = [torch.ones(4, 2**20 // 4) for _ in range(16)]
    del again
    assert m.peak_bytes > 48 * 2**20
