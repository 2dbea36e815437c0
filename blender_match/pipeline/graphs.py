"""The graph a match or a re-render names: a bundled graph, a library graph or a ``.sbs`` file."""
from __future__ import annotations

from pathlib import Path

from ..bundled_graphs import BUNDLED, build
from ..diffmat import MaterialGraph
from ..errors import OptionError
from ..library import library_names, load_library_graph
from ..translator import load_sbs_graph


def load_graph(source: str) -> MaterialGraph:
    """A MaterialGraph from a bundled graph's name, a library graph's name or an .sbs path."""
    if source in BUNDLED:
        return build(source)
    if source in library_names():
        return load_library_graph(source)
    if Path(source).suffix.lower() == ".sbs":
        return load_sbs_graph(Path(source))
    raise OptionError(f"{source}: not a bundled graph ({', '.join(sorted(BUNDLED))}), a library graph "
                      f"({', '.join(library_names()) or 'none built'}) nor a .sbs file")
