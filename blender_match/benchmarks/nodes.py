"""``blender-match bench nodes``: speed and memory of the engine on a production-sized graph.

The graph is the bundled example material (50 nodes, generators and filters as in a real
Substance material). Figures: forward and backward time and peak memory at 512², forward at 2048²,
on the current device. Issue-2 targets on a 2-core CPU: 512² forward < 0.3 s, backward < 0.6 s;
2048² forward < 5 s and < 4 GiB.
"""
from __future__ import annotations

import torch

from .measure import best_of

TARGETS = {"forward_512": 0.3, "backward_512": 0.6, "forward_2048": 5.0}


def run(device: str = "cpu", repeats: int = 3) -> list[dict]:
    from ..bundled_graphs import build

    graph = build("example").to(device)
    rows = []
    nodes = len(graph.order())

    def forward(size):
        with torch.no_grad():
            graph(size=size, seed=0)

    def forward_backward(size):
        maps = graph(size=size, seed=0)
        loss = sum(m.mean() for m in maps.values())
        loss.backward()
        graph.zero_grad(set_to_none=True)

    graph(size=512)  # warm the constant-node cache, as an optimisation loop does
    fwd = best_of(lambda: forward(512), repeats, device)
    both = best_of(lambda: forward_backward(512), repeats, device)
    rows.append({"case": "forward 512²", "nodes": nodes, "seconds": fwd.seconds,
                 "peak_mib": fwd.peak_bytes / 2**20, "target_s": TARGETS["forward_512"]})
    rows.append({"case": "backward 512²", "nodes": nodes, "seconds": max(both.seconds - fwd.seconds, 0.0),
                 "peak_mib": both.peak_bytes / 2**20, "target_s": TARGETS["backward_512"]})
    graph.clear_cache()
    big = best_of(lambda: forward(2048), 1, device)
    rows.append({"case": "forward 2048² (cold)", "nodes": nodes, "seconds": big.seconds,
                 "peak_mib": big.peak_bytes / 2**20, "target_s": TARGETS["forward_2048"]})
    return rows
