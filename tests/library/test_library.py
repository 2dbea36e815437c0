"""The material library: every source builds, its shipped .sbs/.json are up to date, it translates
with no pass-through node into a graph that evaluates to the source's maps, its maps tile, its
random variants differ; and the CLI (library --json / --sheet, render NAME --sample).

Materials are discovered from ``blender_match/library/sources``, so new ones join automatically.
Maps are checked for tiling at 512 and at 2048 for every graph.
"""
from __future__ import annotations

import json
import math
import os
from functools import lru_cache

import pytest
import torch
from imagecheck import assert_tiles

from blender_match.cli import main
from blender_match.diffmat.errors import DiffMatError
from blender_match.diffmat.params_file import apply_params, load_params
from blender_match.diffmat.render import render_maps
from blender_match.library import (
    GRAPHS_DIR,
    build_source,
    library_entry,
    library_names,
    load_library_graph,
    sample_params,
    source_names,
)
from blender_match.library.build import build_one, sample_ranges

SOURCES = source_names()
USAGES = {"basecolor", "normal", "roughness", "metallic", "height"}


@lru_cache(maxsize=None)
def translated(name):
    return load_library_graph(name)


def test_the_library_ships_every_source():
    assert len(SOURCES) >= 4
    assert set(SOURCES) <= set(library_names()), "run python -m blender_match.library.build"


@pytest.mark.parametrize("name", SOURCES)
def test_source_builds_and_is_shipped_up_to_date(name):
    graph = build_source(name)
    assert USAGES <= set(graph.outputs)
    sbs, meta = build_one(name)
    assert (GRAPHS_DIR / f"{name}.sbs").read_text(encoding="utf-8") == sbs, "re-run the library build"
    assert (GRAPHS_DIR / f"{name}.json").read_text(encoding="utf-8") == meta, "re-run the library build"


@pytest.mark.parametrize("name", SOURCES)
def test_graph_translates_without_passthrough_within_bounds(name):
    graph = translated(name)
    report = graph.report
    entry = library_entry(name)
    assert report["nodes_passthrough"] == 0 and not report["unsupported"]
    assert report["channel_adapters"] == 0
    assert 20 <= entry["nodes"] <= 150 and entry["nodes"] == len(graph.nodes)
    assert 30 <= entry["params_optimizable"] <= 200 and entry["params_optimizable"] == graph.num_params()
    assert 3 <= len(entry["exposed"]) <= 12 and entry["exposed"] == list(graph.exposed.kinds)
    assert report["bindings"] >= len(entry["exposed"]) // 2
    # a sampling range for every optimisable parameter, keyed by the translated graph's names
    slots = {f"{n}.{p}": k for n, p, k in graph.param_slots()}
    assert set(entry["sample_ranges"]) == set(slots)
    for key, (lo, hi) in entry["sample_ranges"].items():
        los, his = (lo, hi) if isinstance(lo, list) else ([lo], [hi])
        assert len(los) == len(his) == slots[key]
        assert all(a <= b for a, b in zip(los, his)), key


@pytest.mark.parametrize("name", SOURCES)
def test_round_trip_maps_equal_the_source(name):
    source, graph = build_source(name), translated(name)
    with torch.no_grad():
        a, b = source(size=64, seed=3), graph(size=64, seed=3)
    assert set(a) == set(b)
    for usage in a:
        assert a[usage].shape == b[usage].shape, usage
        assert torch.allclose(a[usage], b[usage], atol=1e-5), (usage, float((a[usage] - b[usage]).abs().max()))


def _check_maps(maps, size):
    assert USAGES <= set(maps)
    for usage, img in maps.items():
        assert img.shape[-2:] == (size, size) and torch.isfinite(img).all(), usage
        assert img.min() >= -1e-6 and img.max() <= 1 + 1e-6, usage
        assert_tiles(img)


@pytest.mark.parametrize("name", SOURCES)
def test_maps_tile_and_are_plausible_at_512(name):
    with torch.no_grad():
        maps = translated(name)(size=512)
    _check_maps(maps, 512)
    metallic = maps["metallic"].mean().item()
    assert metallic < 0.05 or metallic > 0.2  # dielectric, or a metal (possibly partly covered)
    rough = maps["roughness"]
    assert 0.02 <= rough.mean().item() <= 0.98


@pytest.mark.parametrize("name", SOURCES)
def test_maps_tile_at_2048(name):
    with torch.no_grad():
        maps = translated(name)(size=2048)
    _check_maps(maps, 2048)


@pytest.mark.parametrize("name", SOURCES)
def test_random_samples_are_finite_and_differ(name):
    p1, p2 = sample_params(name, 1), sample_params(name, 2)
    assert p1 == sample_params(name, 1) and p1 != p2
    assert set(p1) == set(library_entry(name)["sample_ranges"])
    renders = []
    graph = load_library_graph(name)
    for params in (p1, p2):  # each sample sets every optimisable parameter
        apply_params(graph, params, "sample")
        with torch.no_grad():
            maps = graph(size=64)
            assert all(torch.isfinite(m).all() for m in maps.values())
            renders.append(render_maps(maps))
    assert (renders[0] - renders[1]).abs().mean().item() > 0.01


@pytest.mark.parametrize("name", SOURCES)
def test_a_dielectric_stays_dielectric_whatever_the_parameters(name):
    """A constant metallic map (``constant_map``: a function-driven uniform) is bound, not
    optimised: no parameter vector can make a dielectric metallic."""
    graph = translated(name)
    with torch.no_grad():
        default = graph(size=32)["metallic"]
        if default.max() > 0:
            pytest.skip(f"{name} is not a dielectric")
        extremes = torch.stack([torch.zeros(graph.num_params()), torch.ones(graph.num_params())])
        assert graph(size=32, theta=extremes)["metallic"].max().item() == 0.0


def test_cli_library_json_lists_every_graph(capsys):
    assert main(["library", "--json"]) == 0
    rows = json.loads(capsys.readouterr().out)
    assert [r["name"] for r in rows] == library_names()
    for r in rows:
        assert set(r) == {"name", "library", "family", "file", "nodes", "params_optimizable", "exposed"}
        assert r["file"].endswith(f"{r['name']}.sbs") and os.path.isfile(r["file"])


def test_cli_render_sample_writes_params_that_render_back(tmp_path, capsys):
    name = SOURCES[0]
    out = tmp_path / "s"
    assert main(["render", name, "--size", "64", "--out", str(out), "--sample", "4"]) == 0
    data = json.loads((out / "params.json").read_text())
    assert data["graph"] == name and data["params"] == sample_params(name, 4)
    assert (out / "render.png").is_file() and (out / "basecolor.png").is_file()
    graph = load_library_graph(name)
    load_params(graph, out / "params.json")  # the file is a valid parameter file
    capsys.readouterr()
    assert main(["render", name, "--size", "64", "--out", str(out), "--sample", "4"]) == 2
    assert "already exists" in capsys.readouterr().err
    assert main(["render", "no_such_material", "--out", str(tmp_path / "x"), "--sample", "1"]) == 2
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1 and "no_such_material" in err
    with pytest.raises(SystemExit):
        main(["render", name, "--out", str(tmp_path / "y"), "--sample", "1", "--params", "p.json"])


def test_cli_library_sheet(tmp_path, capsys):
    from PIL import Image

    from blender_match.cli.library import COLUMNS

    sheet = tmp_path / "sheet.png"
    assert main(["library", "--sheet", str(sheet), "--size", "32"]) == 0
    img = Image.open(sheet)
    n = len(library_names())
    cols = min(COLUMNS, n)
    assert img.size == (cols * 32, math.ceil(n / cols) * (32 + 18))
    capsys.readouterr()
    assert main(["library", "--sheet", str(sheet), "--size", "32"]) == 2
    assert "already exists" in capsys.readouterr().err
    assert main(["library", "--sheet", str(sheet), "--size", "32", "--overwrite"]) == 0


def test_graphs_grouped_by_family_in_catalogue_order():
    from blender_match.library.catalog import FAMILIES, by_family, family_of

    names = by_family(library_names())
    assert sorted(names) == sorted(library_names())
    order = list(FAMILIES)
    places = [order.index(family_of(library_entry(n))) for n in names]
    assert places == sorted(places) and len(set(places)) >= 5
    assert family_of({"family": "wood", "library": "user"}) is None and family_of({"family": "nope"}) is None


def test_unlisted_colours_keep_their_hue_in_every_variant():
    """A colour the source did not list moves as a whole (one fraction of its range for every
    component): a grey stays grey instead of taking a random tint."""
    entry = library_entry("plaster")
    together = entry["sample_together"]
    assert together and set(together) <= set(entry["sample_ranges"])
    for k in range(4):
        variant = sample_params(entry["name"], k)
        for key in together:
            lo, hi = entry["sample_ranges"][key]
            fractions = {round((v - a) / (b - a), 4) for v, a, b in zip(variant[key], lo, hi) if b - a > 1e-3}
            assert len(fractions) <= 1, (key, variant[key])


def test_a_listed_colour_named_together_stays_on_its_line():
    """A source's SAMPLE_TOGETHER keeps a listed colour range as a line (varnished wood: dark
    walnut to blond, never a green or purple wood), while a listed range it does not name is drawn
    channel by channel."""
    entry = library_entry("varnished_wood")
    assert "exposed.wood_color" in entry["sample_together"]
    lo, hi = entry["sample_ranges"]["exposed.wood_color"]
    for k in range(6):
        color = sample_params("varnished_wood", k)["exposed.wood_color"]
        fractions = [(v - a) / (b - a) for v, a, b in zip(color, lo, hi)]
        assert max(fractions) - min(fractions) < 1e-3, color
        assert color[0] > color[1] > color[2], color
    assert "exposed.paint_color" not in library_entry("painted_metal")["sample_together"]


def test_sample_together_must_name_a_listed_range():
    graph = load_library_graph("varnished_wood")
    with pytest.raises(DiffMatError, match="SAMPLE_TOGETHER names exposed.tint, not in SAMPLE_RANGES"):
        sample_ranges(graph, {}, {}, "varnished_wood", ("exposed.tint",))


def test_unlisted_parameters_vary_around_their_value():
    from blender_match.library.build import default_spread

    assert default_spread(0.5, 0.0, 1.0) == pytest.approx(0.15)  # mid-range: 15% of the range
    assert default_spread(0.04, 0.0, 20.0) == pytest.approx(0.22)  # a small warp stays small (not +-3)
    assert default_spread(0.0, -1.0, 1.0) == pytest.approx(0.02)  # a rotation of 0 barely turns


def test_painted_metal_spans_an_intact_coat_to_a_chipped_one():
    """A painted sheet is most often intact: at wear 0 no bare metal shows, at high wear a good
    part of it does, and the sampled variants (what the bank and the predictor learn from) hold
    both intact and chipped coats."""
    graph = load_library_graph("painted_metal")
    bare = {}
    for wear in (0.0, 0.9):
        apply_params(graph, {"exposed.wear": wear, "exposed.scratches": 0.0}, "test")
        with torch.no_grad():
            bare[wear] = graph(size=128)["metallic"].mean().item()
    assert bare[0.0] < 1e-3 < 0.2 < bare[0.9]
    sampled = []
    for k in range(16):
        apply_params(graph, sample_params("painted_metal", k), "sample")
        with torch.no_grad():
            metallic = graph(size=64)["metallic"]
        assert metallic.min().item() == 0.0  # the paint is a dielectric in every variant
        sampled.append((metallic > 0.5).float().mean().item())
    assert sum(m < 0.005 for m in sampled) >= 3 and sum(m > 0.05 for m in sampled) >= 3, sampled


def test_dust_lies_on_a_coat_as_light_rough_specks():
    """``dust`` adds specks to the painted metal's coat: lighter and rougher than the paint where
    they lie, none at 0."""
    graph = load_library_graph("painted_metal")
    maps = {}
    for dust in (0.0, 1.0):
        apply_params(graph, {"exposed.wear": 0.0, "exposed.scratches": 0.0, "exposed.dust": dust,
                             "exposed.paint_color": [0.05, 0.05, 0.05]}, "test")
        with torch.no_grad():
            maps[dust] = graph(size=256)
    assert maps[0.0]["roughness"].max().item() < 0.6 < maps[1.0]["roughness"].max().item()
    assert maps[0.0]["basecolor"][:, :3].max().item() < 0.2 < maps[1.0]["basecolor"][:, :3].max().item()
