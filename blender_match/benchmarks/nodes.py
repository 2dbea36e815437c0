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
memory and the engine's caches in place). The last two rows repeat the 512² cases with the
generators' parameters frozen, as the paper optimises (generator outputs cached).
"""
from __future__ import annotations

import torch

from .measure import best_of, in_subprocess, measure

TARGETS = {"forward_512": 0.3, "backward_512": 0.6, "forward_2048": 5.0}


def case(kind: str, size: int, device: str = "cpu", repeats: int = 3, frozen_generators: bool = False) -> dict:
    """One benchmark case in this process: ``kind`` "forward" (no grad) or "backward" (forward,
    loss, backward). Returns the best warm time (or the cold time when ``repeats`` is 0), the cold
    run's peak memory above the baseline, and the node count. ``frozen_generators`` freezes every
    generator's parameters (the MATch paper's setting): their outputs are then cached."""
    from ..bundled_graphs import build

    graph = build("example").to(device)
    if frozen_generators:
        for name, node in graph.nodes.items():
            if node.spec.kind == "generator":
                graph.freeze(name)

    def forward():
        with torch.no_grad():
            graph(size=size, seed=0)

    def forward_backward():
        maps = graph(size=size, seed=0)
        loss = sum(m.mean() for m in maps.values())
        loss.backward()
        graph.zero_grad(set_to_none=True)

    fn = forward if kind == "forward" else forward_backward
    with measure(device) as cold:          # baseline: after imports and graph construction
        fn()
    seconds = best_of(fn, repeats, device).seconds if repeats else cold.seconds
    return {"seconds": seconds, "peak_bytes": cold.peak_bytes, "nodes": len(graph.order())}


def run(device: str = "cpu", repeats: int = 3) -> list[dict]:
    fn = "blender_match.benchmarks.nodes:case"
    fwd = in_subprocess(fn, "forward", 512, device, repeats)
    both = in_subprocess(fn, "backward", 512, device, repeats)
    big = in_subprocess(fn, "forward", 2048, device, 0)
    big_warm = in_subprocess(fn, "forward", 2048, device, 1)
    fwd_frozen = in_subprocess(fn, "forward", 512, device, repeats, True)
    both_frozen = in_subprocess(fn, "backward", 512, device, repeats, True)
    nodes = fwd["nodes"]
    return [
        {"case": "forward 512²", "nodes": nodes, "seconds": fwd["seconds"],
         "peak_mib": fwd["peak_bytes"] / 2**20, "target_s": TARGETS["forward_512"]},
        {"case": "backward 512²", "nodes": nodes, "seconds": max(both["seconds"] - fwd["seconds"], 0.0),
         "peak_mib": both["peak_bytes"] / 2**20, "target_s": TARGETS["backward_512"]},
        {"case": "forward 2048² (cold)", "nodes": nodes, "seconds": big["seconds"],
         "peak_mib": big["peak_bytes"] / 2**20, "target_s": TARGETS["forward_2048"]},
        {"case": "forward 2048² (warm)", "nodes": nodes, "seconds": big_warm["seconds"],
         "peak_mib": big_warm["peak_bytes"] / 2**20, "target_s": TARGETS["forward_2048"]},
        {"case": "forward 512², generators frozen", "nodes": nodes, "seconds": fwd_frozen["seconds"],
         "peak_mib": fwd_frozen["peak_bytes"] / 2**20, "target_s": TARGETS["forward_512"]},
        {"case": "backward 512², generators frozen", "nodes": nodes,
         "seconds": max(both_frozen["seconds"] - fwd_frozen["seconds"], 0.0),
         "peak_mib": both_frozen["peak_bytes"] / 2**20, "target_s": TARGETS["backward_512"]},
    ]
