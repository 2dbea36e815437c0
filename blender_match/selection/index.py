"""One retrieval structure over every library graph's sample bank: which few graphs to render.

Ranking renders each candidate graph at 128 px and scores it with the fit's own style loss
(``selection.rank``): reliable, but a translation and a render per graph, which grows with the
library. The index answers first, for the price of one distance computation, which graphs can
come near the photo at all: the descriptors of every current bank (``selection.bank``; the
user library's included) stacked into one (N, D) matrix with each row's graph, so that a photo's
distance to every sample of every graph is one ``descriptor_distance`` call, and a graph's
distance is that of its nearest sample. Only the ``count`` nearest graphs are then translated and
rendered.

``selection_index(names)`` keeps one index per process for a set of graphs and their staleness
hashes: a bank rebuilt or a graph added makes a new one; adding a graph reads only its own bank.
"""
from __future__ import annotations

import torch

from .bank import bank_path, current_bank, graph_hash
from .descriptor import descriptor_distance


class SelectionIndex:
    """The stacked banks of ``names`` (graphs without a current bank are left out: ``names``
    lists those indexed)."""

    def __init__(self, names, directory=None) -> None:
        self.names: list[str] = []
        descriptors, owners, thetas = [], [], []
        for name in names:
            bank = current_bank(name, directory)
            if bank is None:
                continue
            owners.append(torch.full((bank["descriptors"].shape[0],), len(self.names), dtype=torch.int64))
            descriptors.append(bank["descriptors"].float())
            thetas.append(bank["thetas"])
            self.names.append(name)
        self.descriptors = torch.cat(descriptors) if descriptors else torch.zeros(0, 0)
        self.owners = torch.cat(owners) if owners else torch.zeros(0, dtype=torch.int64)
        self.thetas = thetas

    def nearest_graphs(self, descriptor: torch.Tensor, count: int | None = None) -> list[dict]:
        """The ``count`` graphs (all when None) whose nearest bank sample is closest to the
        descriptor (D,) or (1, D), best first: {"graph", "distance", "theta" (that sample's (P,))}."""
        if not self.names:
            return []
        distances = descriptor_distance(descriptor.reshape(1, -1).float(), self.descriptors)[0]
        best = torch.full((len(self.names),), float("inf")).scatter_reduce(0, self.owners, distances, "amin")
        out = []
        for g in torch.argsort(best)[:count].tolist():
            rows = torch.nonzero(self.owners == g).flatten()
            row = rows[torch.argmin(distances[rows])]
            out.append({"graph": self.names[g], "distance": float(best[g]),
                        "theta": self.thetas[g][row - rows[0]].clone()})
        return out


_INDEXES: dict[tuple, SelectionIndex] = {}


def selection_index(names, directory=None) -> SelectionIndex:
    """The process's index of ``names`` (made anew when a bank file was rewritten or a graph's
    .sbs, metadata or the render revision changed)."""
    key = (str(directory), tuple((n, graph_hash(n), _modified(bank_path(n, directory))) for n in names))
    if key not in _INDEXES:
        _INDEXES.clear()  # one library at a time: an older set is not asked for again
        _INDEXES[key] = SelectionIndex(names, directory)
    return _INDEXES[key]


def _modified(path) -> int:
    return path.stat().st_mtime_ns if path.is_file() else 0
