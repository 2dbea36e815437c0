"""The blender-match command: nodes, coverage, render, translate (in-process, real files)."""
from __future__ import annotations

import json

import pytest

from blender_match.cli import main
from blender_match.diffmat.functional.inputs import load_image as read_image


def test_nodes_json_lists_every_kind_with_parameter_ranges(capsys):
    assert main(["nodes", "--json"]) == 0
    nodes = json.loads(capsys.readouterr().out)
    by_name = {n["name"]: n for n in nodes}
    assert {n["kind"] for n in nodes} == {"atomic", "non_atomic", "generator"}
    for name in ("blend", "levels", "fxmaps", "pixelprocessor", "histogram_scan", "tile_generator"):
        assert name in by_name
    opacity = next(p for p in by_name["blend"]["params"] if p["name"] == "opacitymult")
    assert opacity["min"] == 0 and opacity["max"] == 1 and opacity["optimizable"] is True
    mode = next(p for p in by_name["blend"]["params"] if p["name"] == "blendingmode")
    assert mode["optimizable"] is False and len(mode["choices"]) == 12


def test_coverage_of_real_materials(capsys, shared_dir):
    usage = shared_dir / "reference" / "node_usage.md"
    assert main(["nodes", "--coverage", "--usage", str(usage)]) == 0
    out = capsys.readouterr().out
    shares = [float(line.split("covered: ")[1].split("%")[0]) for line in out.splitlines() if "covered:" in line]
    assert len(shares) == 2 and shares[0] == 100.0 and shares[1] >= 90.0, out


def test_coverage_names_a_missing_usage_file(tmp_path, capsys):
    assert main(["nodes", "--coverage", "--usage", str(tmp_path / "none.md")]) == 2
    assert "none.md: node-usage table not found" in capsys.readouterr().err


def test_render_bundled_example_writes_maps_and_refuses_to_overwrite(tmp_path, capsys):
    out = tmp_path / "maps"
    assert main(["render", "example", "--size", "64", "--out", str(out)]) == 0
    names = {p.name for p in out.iterdir()}
    assert {"basecolor.png", "normal.png", "roughness.png", "metallic.png", "height.png", "render.png"} <= names
    normal = read_image(out / "normal.png")
    assert normal.shape == (1, 4, 64, 64)
    assert 0.4 < normal[0, 2].mean() and normal[0, 2].min() >= 0.5  # OpenGL normals point up (+z)
    before = (out / "basecolor.png").read_bytes()
    assert main(["render", "example", "--size", "64", "--out", str(out)]) == 2
    assert "already exists" in capsys.readouterr().err
    assert (out / "basecolor.png").read_bytes() == before


def test_render_is_deterministic_and_seeded(tmp_path):
    for name, seed in (("a", "3"), ("b", "3"), ("c", "4")):
        assert main(["render", "example", "--size", "32", "--seed", seed, "--out", str(tmp_path / name)]) == 0
    a, b, c = (read_image(tmp_path / n / "height.png") for n in "abc")
    assert (a == b).all() and not (a == c).all()


def test_render_an_sbs_file_and_translate_it(tmp_path, shared_dir, capsys):
    sbs = shared_dir / "data" / "sbs" / "synthoid_OutputSizeExample.sbs"
    assert main(["render", str(sbs), "--size", "32", "--out", str(tmp_path / "r")]) == 0
    assert (tmp_path / "r" / "basecolor.png").is_file()
    report = tmp_path / "report.json"
    assert main(["translate", str(sbs), "--out", str(tmp_path / "prog"), "--report", str(report)]) == 0
    text = report.read_text(encoding="utf-8")
    data = json.loads(text)
    assert text.endswith("}\n") and data["nodes_translated"] >= 0.9 * data["nodes_total"] > 0
    assert list((tmp_path / "prog").glob("*.py"))


@pytest.mark.parametrize("argv, message", [
    (["render", "no_such_graph", "--out", "x"], "not a bundled graph"),
    (["render", "example"], "give a SOURCE and --out"),
    (["render", "example", "--size", "100", "--out", "x"], "not a power-of-two"),
])
def test_render_errors_are_one_line(argv, message, capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert message in err and err.count("\n") == 1
