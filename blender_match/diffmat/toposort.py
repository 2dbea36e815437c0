"""Topological ordering shared by the graph runtime and the translator."""
from __future__ import annotations

from collections import deque


def topological_order(edges: dict[str, list[str]]) -> tuple[list[str], list[str]]:
    """Order the keys of ``edges`` (node -> its sources, all keys of ``edges``) so that sources
    come first; ties keep the input order. Returns (order, stuck): ``stuck`` lists, sorted, the
    nodes left on a cycle (empty when there is none)."""
    indegree = {n: len(set(srcs)) for n, srcs in edges.items()}
    consumers: dict[str, list[str]] = {n: [] for n in edges}
    for n, srcs in edges.items():
        for s in set(srcs):
            consumers[s].append(n)
    queue = deque(n for n in edges if indegree[n] == 0)
    out = []
    while queue:
        n = queue.popleft()
        out.append(n)
        for c in consumers[n]:
            indegree[c] -= 1
            if indegree[c] == 0:
                queue.append(c)
    return out, sorted(n for n in edges if indegree[n] > 0)
