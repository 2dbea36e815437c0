"""``blender-match bench photos``: the category table, a run on one synthetic photo, a missing folder."""
from __future__ import annotations

import json
import math

import numpy as np
import pytest
import torch
from PIL import Image

from blender_match.benchmarks import photos as bench_photos
from blender_match.cli import main
from blender_match.diffmat.render import render_maps
from blender_match.errors import OptionError
from blender_match.library import library_names, load_library_graph


def test_category_table_names_library_graphs():
    table = json.loads(bench_photos.CATEGORIES_FILE.read_text(encoding="utf-8"))["categories"]
    known = set(library_names())
    for category, entry in table.items():
        assert set(entry["graphs"]) <= known, category
        assert entry["why"].strip(), category
    assert bench_photos.load_families()["misc"] == []
    photos = json.loads(bench_photos.CATEGORIES_FILE.read_text(encoding="utf-8"))["photos"]
    for name, entry in photos.items():
        assert entry["category"] in table and table[entry["category"]]["graphs"], name
        assert entry["why"].strip(), name
    assert bench_photos.load_photo_labels() == {name: entry["category"] for name, entry in photos.items()}


def test_photo_labels_refuse_a_broken_table(tmp_path):
    path = tmp_path / "table.json"
    path.write_text('{"categories": {}, "photos": {"a.jpg": "stone"}}')
    with pytest.raises(OptionError, match="table.json: not a photo category table"):
        bench_photos.load_photo_labels(path)


def test_categories_from_sources_then_names(tmp_path):
    (tmp_path / "SOURCES.tsv").write_text("file\tnote\tattributes\nstone_1.jpg\tx\tstone,dirty\nmisc_2.jpg\ty\t-\n")
    assert bench_photos.listed_categories(tmp_path) == {"stone_1.jpg": "stone", "misc_2.jpg": "misc"}
    (tmp_path / "SOURCES.tsv").write_text("file\tnote\nreal_wood_x.png\tno attributes column\n")
    assert bench_photos.listed_categories(tmp_path) == {}
    known = bench_photos.load_families()
    assert bench_photos.name_category("real_asphalt_gravel_desch18", known) == "asphalt"
    assert bench_photos.name_category("brick_wall", known) == "brick"


@pytest.fixture
def one_photo(tmp_path):
    """A folder with the plaster graph's flash render as a 256 px PNG, listed as plaster."""
    with torch.no_grad():
        image = render_maps(load_library_graph("plaster")(size=256, seed=3))[0].clamp(0, 1)
    folder = tmp_path / "photos"
    folder.mkdir()
    Image.fromarray(np.rint(image.permute(1, 2, 0).numpy() * 255).astype(np.uint8)).save(folder / "wall_01.png")
    (folder / "SOURCES.tsv").write_text("file\tattributes\nwall_01.png\tplaster,dirty\n")
    return folder


def test_run_writes_results_and_survives_a_broken_photo(one_photo, tmp_path):
    (one_photo / "broken.png").write_bytes(b"not a png")
    out = tmp_path / "out"
    printed = bench_photos.run(photos=one_photo, quick=True, iterations=4, out=out)
    assert [r["photo"] for r in printed] == ["broken.png", "wall_01.png", "all"]
    assert all(list(r) == list(bench_photos.COLUMNS) for r in printed)  # one table for the CLI
    results = json.loads((out / "results.json").read_text())
    broken, row = results["rows"]
    assert "broken.png" in broken["error"] and broken["family_match"] is False
    assert results["summary"]["failed"] == 1
    assert row["error"] == "" and row["category"] == "plaster"
    assert row["graph"] in row["top3"] and len(row["top3"]) == 3
    assert row["top3"] == [e["graph"] for e in row["ranking"][:3]]
    assert [f["graph"] for f in row["fitted"]] == [row["graph"]]
    assert results["summary"]["family_match_share_listed"] == results["summary"]["family_match_share"]
    assert row["family_match"] == (row["graph"] == "plaster")
    for key in ("seconds", "loss", "patch_distance", "colour_distance", "patch_distance_ideal_flash"):
        assert math.isfinite(row[key]), key
    assert set(row["calibration"]) == {"zoom", "falloff", "basecolor_gain"}
    assert results["config"]["quality"] == "draft" and results["summary"]["photos"] == 2
    assert "wall_01.png" in (out / "results.md").read_text()
    with Image.open(out / "sheet.png") as sheet:
        assert sheet.size == (3 * bench_photos.TILE, 2 * bench_photos.TILE)


def test_missing_folder_is_a_clear_message(tmp_path, capsys):
    assert main(["bench", "photos", "--photos", str(tmp_path / "absent"), "--out", str(tmp_path / "out")]) == 0
    err = capsys.readouterr().err
    assert "no photos" in err and "absent" in err and "Traceback" not in err
    assert not (tmp_path / "out").exists()


def test_a_bad_zoom_is_a_clear_message(capsys):
    with pytest.raises(SystemExit) as exit_info:
        main(["bench", "photos", "--zoom", "x"])
    err = capsys.readouterr().err
    assert exit_info.value.code == 2 and "--zoom" in err and "Traceback" not in err
