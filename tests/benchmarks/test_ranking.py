"""``blender-match bench ranking``: selection alone on a folder of photos."""
from __future__ import annotations

import json

import numpy as np
import torch
from PIL import Image

from blender_match.benchmarks import ranking as bench_ranking
from blender_match.cli import main
from blender_match.diffmat.render import render_maps
from blender_match.library import load_library_graph


def test_family_rank_is_the_first_place_of_the_family():
    ranking = [{"graph": g} for g in ("bark", "plaster", "stucco")]
    assert bench_ranking.family_rank(ranking, ["stucco", "plaster"]) == 2
    assert bench_ranking.family_rank(ranking, ["leather"]) is None


def test_run_ranks_each_photo_and_survives_a_broken_one(tmp_path):
    folder = tmp_path / "photos"
    folder.mkdir()
    with torch.no_grad():
        image = render_maps(load_library_graph("plaster")(size=256, seed=3))[0].clamp(0, 1)
    Image.fromarray(np.rint(image.permute(1, 2, 0).numpy() * 255).astype(np.uint8)).save(folder / "wall_01.png")
    (folder / "SOURCES.tsv").write_text("file\tattributes\nwall_01.png\tplaster\n")
    (folder / "broken.png").write_bytes(b"not a png")
    out = tmp_path / "out"
    printed = bench_ranking.run(photos=folder, out=out)
    assert [r["photo"] for r in printed] == ["broken.png", "wall_01.png", "all"]
    results = json.loads((out / "results.json").read_text())
    broken, row = results["rows"]
    assert "broken.png" in broken["error"] and broken["family_rank"] is None
    assert row["error"] == "" and row["category"] == "plaster"
    names = [e["graph"] for e in row["ranking"]]
    assert row["first"] == names[0] and row["top3"] == names[:3]
    assert row["family_rank"] == min(names.index(g) + 1 for g in ("plaster", "stucco") if g in names)
    summary = results["summary"]
    assert summary["photos"] == 2 and summary["failed"] == 1
    assert summary["family_first"] == (0.5 if row["family_rank"] == 1 else 0.0)
    assert summary["family_first"] <= summary["family_top3"] <= summary["family_ranked"] == 0.5
    assert "wall_01.png" in (out / "results.md").read_text()


def test_no_photos_is_a_clear_message(tmp_path, capsys):
    assert main(["bench", "ranking", "--photos", str(tmp_path / "absent")]) == 0
    err = capsys.readouterr().err
    assert "no photos" in err and "absent" in err and "Traceback" not in err
