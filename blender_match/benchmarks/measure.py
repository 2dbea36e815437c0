"""Timing and peak-memory measurement on CPU (and CUDA where used)."""
from __future__ import annotations

import json
import resource
import subprocess
import sys
import time
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

import torch

from ..allocator import release_freed_memory

_STATUS = Path("/proc/self/status")
_CLEAR_REFS = Path("/proc/self/clear_refs")


def _peak_rss_bytes() -> int:
    if _STATUS.exists():
        for line in _STATUS.read_text().splitlines():
            if line.startswith("VmHWM:"):
                return int(line.split()[1]) * 1024
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024


def _current_rss_bytes() -> int:
    if _STATUS.exists():
        for line in _STATUS.read_text().splitlines():
            if line.startswith("VmRSS:"):
                return int(line.split()[1]) * 1024
    return 0


def _reset_peak() -> bool:
    """Reset the kernel's peak-RSS mark (Linux); False where that is not possible."""
    try:
        _CLEAR_REFS.write_text("5")
        return True
    except OSError:
        return False


class Measurement:
    seconds: float = 0.0
    peak_bytes: int = 0


@contextmanager
def measure(device: str = "cpu") -> Iterator[Measurement]:
    """Measure wall time and the peak memory added while the block runs.

    CPU: peak resident set size above the resident size at entry (Linux resets the peak mark first,
    after handing the freed memory the process keeps back to the system).
    CUDA: ``torch.cuda.max_memory_allocated`` above the allocation at entry.
    """
    m = Measurement()
    if device.startswith("cuda"):
        torch.cuda.synchronize()
        torch.cuda.reset_peak_memory_stats()
        base = torch.cuda.memory_allocated()
    else:
        release_freed_memory()  # what earlier runs left in the allocator's pool is not this run's
        _reset_peak()
        base = _current_rss_bytes()
    start = time.perf_counter()
    yield m
    if device.startswith("cuda"):
        torch.cuda.synchronize()
        m.peak_bytes = torch.cuda.max_memory_allocated() - base
    else:
        m.peak_bytes = max(0, _peak_rss_bytes() - base)
    m.seconds = time.perf_counter() - start


def best_of(fn, repeats: int = 3, device: str = "cpu") -> Measurement:
    """The fastest of ``repeats`` runs of ``fn`` (its peak memory is the largest seen)."""
    best: Measurement | None = None
    peak = 0
    for _ in range(repeats):
        with measure(device) as m:
            fn()
        peak = max(peak, m.peak_bytes)
        if best is None or m.seconds < best.seconds:
            best = m
    if best is None:
        raise ValueError(f"best_of: repeats must be at least 1, not {repeats}")
    best.peak_bytes = peak
    return best


def in_subprocess(function: str, *args, threads: int | None = None, timeout: float = 600.0):
    """Run ``function`` ("package.module:name", returning a JSON-serialisable value) with ``args``
    in a fresh Python process and return its result.

    A fresh process gives a meaningful peak memory: the kernel's peak-RSS mark of a process that
    has only imported, built and run one case, rather than that of a process whose allocator has
    already grown to hold every earlier case (which then shows ~0 added peak).
    """

    threads = threads or torch.get_num_threads()
    module, _, name = function.partition(":")
    code = ("from blender_match.allocator import keep_freed_memory\n"
            "keep_freed_memory()\n"
            "import json, sys, torch\n"
            f"torch.set_num_threads({int(threads)})\n"
            f"from {module} import {name} as f\n"
            f"r = f(*json.loads(sys.argv[1]))\n"
            "sys.stdout.write('\\n@@RESULT ' + json.dumps(r) + '\\n')\n")
    proc = subprocess.run([sys.executable, "-c", code, json.dumps(list(args))], capture_output=True,
                          text=True, timeout=timeout)
    if proc.returncode != 0:
        raise RuntimeError(f"benchmark subprocess {function} failed:\n{proc.stderr[-2000:]}")
    for line in reversed(proc.stdout.splitlines()):
        if line.startswith("@@RESULT "):
            return json.loads(line[len("@@RESULT "):])
    raise RuntimeError(f"benchmark subprocess {function} printed no result")
