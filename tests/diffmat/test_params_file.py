"""Parameter files: round trip, and a clear error for every kind of bad entry."""
from __future__ import annotations

import json

import pytest
import torch

from blender_match.diffmat import DiffMatError, MaterialGraph
from blender_match.diffmat.params_file import graph_params, load_params, save_params
from blender_match.safe_files import FileWriteError


def small_graph() -> MaterialGraph:
    g = MaterialGraph("small")
    g.add("noise", "perlin_noise_zoom", scale=8.0)
    g.add("lv", "levels", {"input1": "noise"}, levelinlow=(0.1, 0.1, 0.1, 0.0))
    g.set_output("roughness", "lv")
    return g


def test_round_trip_reproduces_the_maps(tmp_path):
    g = small_graph()
    g.nodes["lv"].set_values(levelinhigh=(0.7, 0.7, 0.7, 1.0))
    save_params(g, tmp_path / "p.json")
    assert (tmp_path / "p.json").read_text(encoding="utf-8").endswith("}\n")  # a text file ends its line
    with pytest.raises(FileWriteError, match="already exists"):
        save_params(g, tmp_path / "p.json")
    fresh = small_graph()
    load_params(fresh, tmp_path / "p.json")
    assert graph_params(fresh) == graph_params(g)
    torch.testing.assert_close(fresh(size=32)["roughness"], g(size=32)["roughness"])


@pytest.mark.parametrize("entry, message", [
    ({"lv.levelinlow": [2.0, 0, 0, 0]}, "outside"),
    ({"lv.levelinlow": [0.1, 0.1]}, "component"),
    ({"nope.x": 1.0}, "unknown node 'nope'"),
    ({"lv.gamma": 1.0}, "no continuous parameter 'gamma'"),
    ({"noise.scale": "big"}, "finite number"),
])
def test_bad_entries_name_the_file_and_change_nothing(tmp_path, entry, message):
    g = small_graph()
    before = graph_params(g)
    path = tmp_path / "bad.json"
    path.write_text(json.dumps({"params": {"noise.scale": 4.0, **entry}}))
    with pytest.raises(DiffMatError, match=message) as err:
        load_params(g, path)
    assert str(path) in str(err.value)
    assert graph_params(g) == before


def test_unreadable_files(tmp_path):
    g = small_graph()
    with pytest.raises(DiffMatError, match="not found"):
        load_params(g, tmp_path / "missing.json")
    (tmp_path / "broken.json").write_text("{not json")
    with pytest.raises(DiffMatError, match="not a readable JSON"):
        load_params(g, tmp_path / "broken.json")
    (tmp_path / "list.json").write_text("[1, 2]")
    with pytest.raises(DiffMatError, match="params"):
        load_params(g, tmp_path / "list.json")
