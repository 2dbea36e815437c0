"""Identifier and name variants found in real production .sbs files (hand-written snippets, not
copies): parameter identifiers of other library versions, vector parameters spread over several
spec parameters, legacy value ranges, input-slot spellings, library-name spellings."""
from __future__ import annotations

import math

import pytest
import sbs_snippets as W
import torch

from blender_match.diffmat import get_spec
from blender_match.translator import aliases, translate

SIZE = 32


def _write(tmp_path, text, name="doc.sbs"):
    path = tmp_path / name
    path.write_text(text)
    return path


def _one_instance(tmp_path, graph_name, params, dep="sbs://lib.sbs", out_ident="output", conns=(), extra=()):
    nodes = [W.instance_node(10, f"pkg:///{graph_name}?dependency=3", params=params, conns=conns,
                             outputs=[(11, out_ident, 2)]), *extra, W.output_node(20, 100, 10, 11)]
    doc = W.package([W.graph("G", nodes, outputs=[(100, "h", "height")])], dependencies=[(3, dep)])
    return translate(_write(tmp_path, doc))


def _values(t, spec_name):
    node = next(n for n in t.graph.nodes.values() if n.spec.name == spec_name)
    out = dict(node.fixed)
    for k, v in node.values().items():
        v = v.detach().flatten().tolist()
        out[k] = v[0] if len(v) == 1 else v
    return out, node


def test_normalisation_and_resolution_rules():
    assert aliases.norm("Luminance_Variation-Contrast") == "luminance_variation_contrast"
    tile = get_spec("tile_generator")
    assert aliases.resolve_param(tile, "Pattern_Size") == [("size_xy", None)]
    assert aliases.resolve_param(tile, "position_offset") == [("offset", None)]
    assert aliases.resolve_param(tile, "X_Amount") == [("x_amount", None)]
    assert aliases.resolve_param(tile, "no_such_thing") == []
    assert aliases.resolve_param(tile, "Pattern_Type") == [("pattern", None)]
    assert aliases.resolve_param(tile, "CheckerMask") == [("checker_mask", None)]      # underscores squashed
    assert aliases.resolve_param(tile, "RandomMask") == [("mask_random", None)]
    assert aliases.resolve_param(tile, "BlendingMode") == [("blending_mode", None)]   # legacy and current
    assert aliases.resolve_param(tile, "blending_mode") == [("blending_mode", None)]
    assert aliases.resolve_param(tile, "GlobalOpacity") == [("global_opacity", None)]
    assert aliases.resolve_param(tile, "background_color") == [("background_level", None)]   # grey here
    # the older Tile Generator: free rotation and its spread in degrees, a scale variation
    assert aliases.resolve_param(tile, "Free_Rotation") == [("rotation", None)]
    assert aliases.resolve_param(tile, "Free_Rotation_Random") == [("rotation_random", None)]
    assert aliases.resolve_param(tile, "ScaleVariation") == [("scale_random", None)]
    assert aliases.convert_value("tile_generator", "rotation", "Free_Rotation", 45.0) == 0.125
    # a spread of that many degrees in all: ± half of it, in turns (360: any angle)
    assert aliases.convert_value("tile_generator", "rotation_random", "Free_Rotation_Random", 360.0) == 0.5
    assert aliases.convert_value("tile_generator", "rotation_random", "Free_Rotation_Random", 720.0) == 0.5
    assert aliases.convert_value("tile_generator", "rotation_random", "Free_Rotation_Random", 36.0) == 0.05
    assert aliases.resolve_param(tile, "LuminanceByScaleVariation") == [("luminance_by_scale", None)]
    assert aliases.resolve_param(tile, "ScaleVariation_Seed") == [("scale_random_seed", None)]
    assert aliases.resolve_param(tile, "scale_random_seed") == [("scale_random_seed", None)]
    assert aliases.resolve_param(tile, "offset_random_seed") == [("offset_random_seed", None)]
    assert aliases.resolve_param(tile, "position_offset_random") == [("offset_random", None)]
    assert aliases.resolve_param(get_spec("anisotropic_noise"), "y_by_resolution") == \
        [("y_amount_by_resolution", None)]
    assert aliases.resolve_param(get_spec("parquet_1"), "luminance_variation") == [("luminance_random", None)]
    assert aliases.resolve_param(get_spec("brick_generator"), "Height") == [("height", None)]
    assert aliases.resolve_param(tile, "Vertical_Offset") == [("vertical_offset", None)]
    assert aliases.resolve_param(tile, "Global_Offset") == [("global_offset", None)]
    assert aliases.resolve_param(tile, "reverse_rendering_order") == [("reverse_rendering_order", None)]
    colour = get_spec("tile_generator_color")
    assert aliases.resolve_param(colour, "Nb_X") == [("x_amount", None)]           # 64 in a production granite
    assert aliases.resolve_param(colour, "Color_Variation") == [("color_random", None)]
    assert aliases.resolve_param(get_spec("cells_1"), "Distance") == [("scale", None)]
    scratches = get_spec("scratches_generator")
    assert aliases.resolve_param(scratches, "scratches_width") == [("width", None)]   # node-word prefix
    levels = get_spec("levels")
    assert aliases.resolve_param(levels, "Level-In-Low") == [("levelinlow", None)]   # underscores squashed
    assert aliases.resolve_input(get_spec("histogram_scan"), "Input1") == "input_1"
    assert aliases.resolve_input(get_spec("levels"), "Input_1") == "input1"
    assert aliases.convert_value("crystal_1", "disorder", "Disorder", 50.0) == 0.5
    assert aliases.convert_value("crystal_1", "disorder", "disorder", 0.3) == 0.3
    assert aliases.convert_value("gradient_linear_1", "rotation", "rotation", 1) == 0.25
    scratches = get_spec("scratches_generator")
    assert aliases.resolve_param(scratches, "spline_rotation") == [("angle", None)]
    assert aliases.resolve_param(scratches, "Spline_Number") == [("amount", None)]
    assert aliases.convert_value("scratches_generator", "amount", "spline_number", 26) == 4   # 2 x 4² ≈ 26
    # the older identifier counts every scratch too: a production file's 3965 is a lattice of 45, not 64
    assert aliases.convert_value("scratches_generator", "amount", "scratches_amount", 26) == 4
    assert aliases.convert_value("scratches_generator", "amount", "scratches_amount", 3965) == 45
    assert aliases.convert_value("gradient_linear_1", "rotation", "rotation", 0.5) == 0.5


def test_shape_size_and_legacy_noise_distance(tmp_path):
    t = _one_instance(tmp_path, "shape", [W.param("Size", "constantValueFloat1", 0.4),
                                          W.param("Rotation", "constantValueBool", 1)], out_ident="Simple_Shape")
    assert t.report["params_dropped"] == 0 and not t.report["params_dropped_names"]
    vals, _ = _values(t, "shape")
    assert math.isclose(vals["scale"], 0.4, abs_tol=1e-6)
    assert vals["rotation_45"] is True
    t = _one_instance(tmp_path, "perlin_noise_zoom", [W.param("Distance", "constantValueInt32", 6),
                                                      W.param("Disorder", "constantValueFloat1", 34.0)],
                      out_ident="Noise_Zoom")
    vals, _ = _values(t, "perlin_noise_zoom")
    assert math.isclose(vals["scale"], 6.0, abs_tol=1e-5) and math.isclose(vals["disorder"], 0.34, abs_tol=1e-5)
    assert torch.isfinite(t.graph(size=SIZE)["height"]).all()


def test_stripes_count_is_read_from_its_library_identifier(tmp_path):
    """The library's Stripes names its count ``Stripes`` (a production zebra skin sets 30 and a
    Shift of 30 for 45-degree stripes); it was dropped, so the node drew its default 10."""
    t = _one_instance(tmp_path, "stripes", [W.param("Stripes", "constantValueInt32", 30),
                                            W.param("Shift", "constantValueInt32", 30)], out_ident="Stripes")
    assert t.report["params_dropped"] == 0
    vals, _ = _values(t, "stripes")
    assert (vals["number"], vals["shift"]) == (30, 30)


def test_an_integer_past_its_slider_is_used_or_clamped(tmp_path):
    """Substance takes slider ranges as hints: a production file's Tile Generator of 100 x 100
    tiles was drawn with the default 10 x 10. An integer past the spec's range is now clamped to
    it (and reported), one within the engine's range used as it is (production files set 500)."""
    t = _one_instance(tmp_path, "tile_generator", [W.param("X_Amount", "constantValueInt32", 500),
                                                   W.param("Y_Amount", "constantValueInt32", 2000)],
                      out_ident="TileGenerator")
    vals, _ = _values(t, "tile_generator")
    assert (vals["x_amount"], vals["y_amount"]) == (500, 1024)
    assert any("y_amount: value 2000 is outside [1, 1024]; 1024 used" in w for w in t.report["warnings"])


def test_vector_parameter_spread_over_components(tmp_path):
    t = _one_instance(tmp_path, "brick_generator", [W.param("Bricks", "constantValueInt2", "3 9"),
                                                    W.param("Bevel", "constantValueFloat4", "0.1 0.2 1 1")],
                      out_ident="Bricks_Generator")
    vals, _ = _values(t, "brick_generator")
    assert (vals["x_amount"], vals["y_amount"]) == (3, 9) and math.isclose(vals["bevel"], 0.1, abs_tol=1e-5)
    assert t.report["params_dropped"] == 0
    assert t.graph(size=SIZE)["height"].shape == (1, 1, SIZE, SIZE)


def test_older_library_parameters_that_were_dropped_now_reach_their_nodes(tmp_path):
    """Read from public production files and dropped before: the Brick Generator's Height and
    Slope, the older Tile Generator's own seeds and Position Offset Random, the older Anisotropic
    Noise's Y By Resolution, the Grunge Maps' Invert."""
    t = _one_instance(tmp_path, "brick_generator", [W.param("Height", "constantValueFloat4", "0.81 0.71 0.38 0.16"),
                                                    W.param("Slope", "constantValueFloat4", "0.26 0.17 0.69 -0.68")],
                      out_ident="Bricks_Generator")
    vals, _ = _values(t, "brick_generator")
    assert vals["height"] == pytest.approx([0.81, 0.71, 0.38, 0.16], abs=1e-5)
    assert vals["slope"] == pytest.approx([0.26, 0.17, 0.69, -0.68], abs=1e-5)
    cases = [("tile_generator", "TileGenerator", [W.param("offset_random_seed", "constantValueInt32", 377),
                                                  W.param("ScaleVariation_Seed", "constantValueInt32", 12),
                                                  W.param("position_offset_random", "constantValueFloat1", 0.5)],
              {"offset_random_seed": 377, "scale_random_seed": 12, "offset_random": 0.5}),
             ("anisotropic_noise", "Anisotropic_Noise", [W.param("y_by_resolution", "constantValueBool", 1)],
              {"y_amount_by_resolution": True}),
             ("grunge_map_013", "output", [W.param("invert", "constantValueBool", 1)], {"invert": True})]
    for graph_name, out_ident, params, expected in cases:
        t = _one_instance(tmp_path, graph_name, params, out_ident=out_ident)
        assert t.report["params_dropped"] == 0, (graph_name, t.report["params_dropped_names"])
        vals, _ = _values(t, graph_name)
        assert {k: vals[k] for k in expected} == pytest.approx(expected), graph_name
        assert torch.isfinite(t.graph(size=SIZE)["height"]).all()


def test_exact_identifier_wins_over_alias(tmp_path):
    t = _one_instance(tmp_path, "tile_generator", [W.param("pattern_size", "constantValueFloat2", "0.3 0.3"),
                                                   W.param("size_xy", "constantValueFloat2", "0.7 0.7")],
                      out_ident="TileGenerator")
    vals, _ = _values(t, "tile_generator")
    assert vals["size_xy"] == pytest.approx([0.7, 0.7], abs=1e-5)


def test_quarter_turn_rotation_and_old_tile_identifiers(tmp_path):
    t = _one_instance(tmp_path, "gradient_linear_1", [W.param("rotation", "constantValueInt32", 1)],
                      out_ident="Simple_Gradient")
    vals, _ = _values(t, "gradient_linear_1")
    assert math.isclose(vals["rotation"], 0.25, abs_tol=1e-6)
    t = _one_instance(tmp_path, "tile_generator",
                      [W.param("Luminance_Variation-Contrast", "constantValueFloat2", "0.34 0"),
                       W.param("Pattern_Specific", "constantValueFloat2", "0.09 0")], out_ident="TileGenerator")
    vals, _ = _values(t, "tile_generator")
    assert math.isclose(vals["luminance_random"], 0.34, abs_tol=1e-5)
    assert math.isclose(vals["pattern_specific"], 0.09, abs_tol=1e-5)


def test_make_it_tile_patch_reads_every_slider_in_its_units(tmp_path):
    """Make It Tile Patch's sizes were dropped and its angles (degrees) read as turns; the
    grayscale node's Luminosity Variation is its colour variation."""
    t = _one_instance(tmp_path, "make_it_tile_patch_grayscale",
                      [W.param("Pattern_size_width", "constantValueFloat1", 361.6),
                       W.param("Pattern_size_height", "constantValueFloat1", 214.5),
                       W.param("Size_Variation", "constantValueFloat1", 36.8),
                       W.param("Rotation", "constantValueFloat1", 90.0),
                       W.param("Rotation_Variation", "constantValueFloat1", 360.0),
                       W.param("Mask_Warping", "constantValueFloat1", 12.4),
                       W.param("Luminosity_Variation", "constantValueFloat1", 0.5),
                       W.param("Octave", "constantValueInt32", 2)],
                      out_ident="Make_It_Tile_Patch_Grayscale")
    assert t.report["params_dropped"] == 0, t.report["params_dropped_names"]
    vals, _ = _values(t, "make_it_tile_patch_grayscale")
    assert vals["pattern_size_width"] == pytest.approx(361.6, abs=1e-3)
    assert vals["pattern_size_height"] == pytest.approx(214.5, abs=1e-3)
    assert vals["size_variation"] == pytest.approx(36.8, abs=1e-3)
    assert vals["rotation"] == pytest.approx(0.25, abs=1e-6)
    assert vals["rotation_variation"] == pytest.approx(1.0, abs=1e-6)
    assert vals["mask_warping"] == pytest.approx(12.4, abs=1e-4)
    assert vals["color_variation"] == pytest.approx(0.5, abs=1e-6) and vals["octave"] == 2
    assert torch.isfinite(t.graph(size=SIZE)["height"]).all()


def test_input_slot_spellings(tmp_path):
    src = W.filter_node(5, "uniform", params=[W.param("outputcolor", "constantValueFloat4", "0.3 0.3 0.3 1"),
                                              W.param("colorswitch", "constantValueBool", 0)], outputs=[(6, 2)])
    t = _one_instance(tmp_path, "histogram_scan", [W.param("Position", "constantValueFloat1", 0.2)],
                      out_ident="Output", conns=[("Input1", 5, 6)], extra=[src])
    assert not any("connection dropped" in w for w in t.report["warnings"])
    node = next(n for n in t.graph.nodes.values() if n.spec.name == "histogram_scan")
    assert node is not None


def test_mosaic_reads_its_source_slot(tmp_path):
    """Mosaic's current slots are Source and Effect: two production leathers connected both, and
    the Source connection was dropped (the node warped nothing)."""
    src = W.filter_node(5, "uniform", params=[W.param("outputcolor", "constantValueFloat4", "0.3 0.3 0.3 1"),
                                              W.param("colorswitch", "constantValueBool", 0)], outputs=[(6, 2)])
    t = _one_instance(tmp_path, "mosaic_grayscale", [W.param("Intensity", "constantValueFloat1", 0.01)],
                      out_ident="Output", conns=[("Source", 5, 6), ("Effect", 5, 6)], extra=[src])
    assert not any("connection dropped" in w for w in t.report["warnings"])
    assert float(t.graph(size=SIZE)["height"].detach().mean()) == pytest.approx(0.3, abs=1e-3)


def test_tile_sampler_draws_its_sixteenth_pattern(tmp_path):
    """Tile Sampler's Pattern list runs one shape past the Tile Generator's, to Hemisphere (16): a
    production ferrofluid sets it, and its tiles were drawn as the default squares."""
    t = _one_instance(tmp_path, "tile_sampler", [W.param("pattern", "constantValueInt32", 16),
                                                 W.param("x_amount", "constantValueInt32", 2),
                                                 W.param("y_amount", "constantValueInt32", 2)], out_ident="output")
    assert not t.report["warnings"]
    vals, _ = _values(t, "tile_sampler")
    assert vals["pattern"] == 16
    height = t.graph(size=64)["height"].detach()[0, 0]
    tile = height[:32, :32]
    # a dome: brightest at the tile's centre, falling off to its corners (a square would be flat)
    assert float(tile[14:18, 14:18].mean()) > float(tile[4:8, 14:18].mean()) + 0.1
    assert float(tile[1, 1]) < 0.05


@pytest.mark.parametrize("name,expected", [("directional_noise", "directionnal_noise"),
                                           ("perlin_noise_zoom_legacy", "perlin_noise_zoom"),
                                           ("curvature_smooth_v2", "curvature_smooth")])
def test_library_name_spellings(tmp_path, name, expected):
    t = _one_instance(tmp_path, name, [])
    assert t.report["nodes_passthrough"] == 0
    assert any(n.spec.name == expected for n in t.graph.nodes.values())


def test_colour_twin_is_an_approximation(tmp_path):
    src = W.filter_node(5, "uniform", params=[W.param("outputcolor", "constantValueFloat4", "0.3 0.6 0.3 1")],
                        outputs=[(6, 1)])
    nodes = [src, W.instance_node(10, "pkg:///blur_hq_color?dependency=3", conns=[("Source", 5, 6)],
                                  outputs=[(11, "Blur_HQ", 1)]),
             W.output_node(20, 100, 10, 11)]
    doc = W.package([W.graph("G", nodes, outputs=[(100, "c", "baseColor")])], dependencies=[(3, "sbs://blur_hq.sbs")])
    t = translate(_write(tmp_path, doc))
    assert t.report["nodes_passthrough"] == 0
    assert any("approximated" in w for w in t.report["warnings"])
    assert torch.isfinite(t.graph(size=SIZE)["basecolor"]).all()
