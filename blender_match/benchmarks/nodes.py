"""``blender-match bench nodes``: speed and memory of the engine on a production-sized graph.

The graph is the bundled example material (50 nodes, generators and filters as in a real
Substance material). Figures: forward and backward time and peak memory at 512², forward at 2048²,
on the current device. Issue-2 targets on a 2-core CPU: 512² forward < 0.3 s, backward < 0.6 s;
2048² forward < 5 s and < 4 GiB.

Each case runs in a fresh process (``measure.in_subprocess``). Its peak memory (``peak_mib``) is
the peak resident memory of that process above its resident memory after the imports and the
graph's construction (CUDA: the peak allocation above the allocation then), measured over the
case's first evaluation, so it is the memory the evaluation itself needs: values, the autograd
graph, FFT and sampling buffers. Times are the best of ``repeats`` warm runs after that one
(the 2048² forward: the cold run itself, then once warm — a re-render, with the process's
memory and the engine's caches in place). "backward" is the backward pass alone
(``loss.backward()``); the forward it follows runs with autograd, which costs more than the
no-grad forward (saved tensors, no in-place fast paths), so both are printed, and their sum,
one optimisation step. The last two rows repeat the 512² cases with the
generators' parameters frozen, as the paper optimises (generator outputs cached).
"""
from __future__ import annotations

import time

import torch

from ..bundled_graphs import build
from .measure import best_of, in_subprocess, measure

TARGETS = {"forward_512": 0.3, "backward_512": 0.6, "forward_2048": 5.0}


def _clock(device: str) -> float:
    if device.startswith("cuda"):
        torch.cuda.synchronize()
    return time.perf_counter()


def case(kind: str, size: int, device: str = "cpu", repeats: int = 3, frozen_generators: bool = False) -> dict:
    """One benchmark case in this process: ``kind`` "forward" (no grad) or "backward" (forward,
    loss, backward). Returns the best warm time (or the cold time when ``repeats`` is 0), the cold
    run's peak memory above the baseline, and the node count. ``frozen_generators`` freezes every
    generator's parameters (the MATch paper's setting): their outputs are then cached."""
    graph = build("example").to(device)
    if frozen_generators:
        for name, node in graph.node_items():
            if node.spec.kind == "generator":
                graph.freeze(name)

    def forward():
        with torch.no_grad():
            graph(size=size, seed=0)

    def forward_backward():
        """One optimisation step; returns (forward with autograd, backward pass) seconds."""
        began = _clock(device)
        maps = graph(size=size, seed=0)
        loss = sum(m.mean() for m in maps.values())
        forwarded = _clock(device)
        loss.backward()
        graph.zero_grad(set_to_none=True)
        return forwarded - began, _clock(device) - forwarded

    if kind == "forward":
        with measure(device) as cold:          # baseline: after imports and graph construction
            forward()
        seconds = best_of(forward, repeats, device).seconds if repeats else cold.seconds
        return {"seconds": seconds, "peak_bytes": cold.peak_bytes, "nodes": len(graph.order())}
    with measure(device) as cold:
        forward_backward()
    steps = [forward_backward() for _ in range(repeats)]
    return {"seconds": min(f + b for f, b in steps), "forward_seconds": min(f for f, _ in steps),
            "backward_seconds": min(b for _, b in steps), "peak_bytes": cold.peak_bytes,
            "nodes": len(graph.order())}


def run(device: str = "cpu", repeats: int = 3) -> list[dict]:
    fn = "blender_match.benchmarks.nodes:case"
    fwd = in_subprocess(fn, "forward", 512, device, repeats)
    both = in_subprocess(fn, "backward", 512, device, repeats)
    big = in_subprocess(fn, "forward", 2048, device, 0)
    big_warm = in_subprocess(fn, "forward", 2048, device, 1)
    fwd_frozen = in_subprocess(fn, "forward", 512, device, repeats, True)
    both_frozen = in_subprocess(fn, "backward", 512, device, repeats, True)
    nodes = fwd["nodes"]

    def row(case, seconds, result, target=None):
        return {"case": case, "nodes": nodes, "seconds": seconds, "peak_mib": result["peak_bytes"] / 2**20,
                "target_s": target}

    return [
        row("forward 512²", fwd["seconds"], fwd, TARGETS["forward_512"]),
        row("forward 512² with autograd", both["forward_seconds"], both),
        row("backward 512²", both["backward_seconds"], both, TARGETS["backward_512"]),
        row("forward + backward 512² (one step)", both["seconds"], both),
        row("forward 2048² (cold)", big["seconds"], big, TARGETS["forward_2048"]),
        row("forward 2048² (warm)", big_warm["seconds"], big_warm, TARGETS["forward_2048"]),
        row("forward 512², generators frozen", fwd_frozen["seconds"], fwd_frozen, TARGETS["forward_512"]),
        row("backward 512², generators frozen", both_frozen["backward_seconds"], both_frozen,
            TARGETS["backward_512"]),
    ]
