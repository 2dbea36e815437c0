"""Translation into DiffMat graphs: mapping, parameters, exposed parameters and modes, instances,
pass-through, sizes, processors, and the six real files."""
from __future__ import annotations

import pytest
import sbs_snippets as W
import torch

from blender_match.diffmat import get_spec
from blender_match.diffmat.nodes import has_spec
from blender_match.translator import TranslatorError, translate

SIZE = 32


def _write(tmp_path, text, name="doc.sbs"):
    path = tmp_path / name
    path.write_text(text)
    return path


def _uniform(uid, color, comptype=1, **kw):
    return W.filter_node(uid, "uniform", params=[W.param("outputcolor", "constantValueFloat4", color)],
                         outputs=[(uid + 1, comptype)], **kw)


def _exposed_doc():
    color = W.dyn_param("outputcolor", 4, [
        W.fnode(1, "get_float1", data=("constantValueString", "level")),
        W.fnode(2, "const_float1", data=("constantValueFloat1", 1.0)),
        W.fnode(3, "vector2", {"componentsin": 1, "componentslast": 1}, type_code=512),
        W.fnode(5, "vector2", {"componentsin": 1, "componentslast": 2}, type_code=512),
        W.fnode(4, "vector4", {"componentsin": 3, "componentslast": 5}, type_code=2048),
    ])
    nodes = [
        W.filter_node(10, "uniform", params=[color], outputs=[(11, 1)]),
        W.filter_node(20, "uniform", params=[W.param("outputcolor", "constantValueFloat4", "0.2 0.2 0.2 1"),
                                             W.param("colorswitch", "constantValueBool", 0)], outputs=[(21, 2)]),
        W.filter_node(30, "uniform", params=[W.param("outputcolor", "constantValueFloat4", "0 0 1 1")],
                      outputs=[(31, 1)]),  # dead: reaches no output
        W.output_node(40, 100, 10, 11),
        W.output_node(41, 101, 20, 21),
    ]
    return W.package([W.graph("Mat", nodes, outputs=[(100, "basecolor", "baseColor"), (101, "rough", "roughness")],
                              paraminputs=[W.paraminput("level", 5, 256, "constantValueFloat1", 0.25, 0, 1)])])


def test_uniform_graph_and_report(tmp_path):
    t = translate(_write(tmp_path, _exposed_doc()))
    out = t.graph(size=SIZE)
    assert out["basecolor"].shape == (1, 4, SIZE, SIZE) and out["roughness"].shape == (1, 1, SIZE, SIZE)
    torch.testing.assert_close(out["basecolor"][0, :, 0, 0], torch.tensor([0.25, 0.25, 0.25, 1.0]))
    torch.testing.assert_close(out["roughness"][0, 0, 0, 0], torch.tensor(0.2))
    r = t.report
    assert (r["nodes_total"], r["nodes_translated"], r["nodes_passthrough"], r["nodes_pruned"]) == (3, 3, 0, 1)
    assert r["bindings"] == 1 and r["exposed"][0]["name"] == "level"
    for key in ("nodes_total", "nodes_translated", "nodes_passthrough", "nodes_pruned", "unsupported",
                "params_optimizable", "outputs", "seconds"):
        assert key in r


def test_exposed_parameters_drive_nodes_differentiably(tmp_path):
    g = translate(_write(tmp_path, _exposed_doc()), mode="exposed").graph
    assert g.param_names() == ["exposed.level"]
    g.exposed.set_values(level=0.75)
    g.clear_cache()
    assert g(size=8)["basecolor"][0, 0, 0, 0].item() == pytest.approx(0.75)
    out = g(size=8)["basecolor"]
    out[:, 0].sum().backward()
    assert g.exposed.theta["level"].grad is not None and g.exposed.theta["level"].grad.abs().item() > 0
    # batched parameter vectors through the exposed parameter
    theta = torch.tensor([[0.1], [0.9]])
    batch = g(size=8, theta=theta)["basecolor"]
    assert batch.shape[0] == 2
    torch.testing.assert_close(batch[:, 0, 0, 0], torch.tensor([0.1, 0.9]))


def test_modes(tmp_path):
    path = _write(tmp_path, _exposed_doc())
    exposed = translate(path, mode="exposed").graph
    plus = translate(path, mode="exposed_plus").graph
    free = translate(path, mode="all").graph
    assert exposed.num_params() == 1
    # exposed_plus: the exposed parameter and the unbound uniform colour (4 components)
    assert plus.num_params() == 1 + 4
    assert "exposed.level" in plus.param_names() and not any(n.startswith("uniform_1.") for n in plus.param_names())
    # all: no exposed parameter; both uniforms' colours free, the folded value as initial value
    assert free.num_params() == 8 and not free.exposed.kinds
    torch.testing.assert_close(free(size=8)["basecolor"][0, :, 0, 0], torch.tensor([0.25, 0.25, 0.25, 1.0]))
    with pytest.raises(TranslatorError):
        translate(path, mode="bogus")


def _blend_doc(extra_nodes=(), blend_params=(), opacity_src=None):
    conns = [("destination", 10, 11), ("source", 20, 21)] + ([("opacity", opacity_src, opacity_src + 1)]
                                                               if opacity_src else [])
    nodes = [_uniform(10, "1 0 0 1"), _uniform(20, "0 0 1 1"),
             W.filter_node(30, "blend", params=list(blend_params), conns=conns, outputs=[(31, 1)]),
             W.output_node(40, 100, 30, 31), *extra_nodes]
    return W.package([W.graph("B", nodes, outputs=[(100, "basecolor", "baseColor")])])


@pytest.mark.skipif(not has_spec("blend"), reason="blend not registered")
def test_blend_parameters_and_defaults(tmp_path):
    doc = _blend_doc(blend_params=[W.param("opacitymult", "constantValueFloat1", 0.25)])
    t = translate(_write(tmp_path, doc))
    node = t.graph.nodes["blend_1"]
    assert node.values()["opacitymult"].item() == pytest.approx(0.25)
    assert node.fixed["blendingmode"] == get_spec("blend").param("blendingmode").default
    torch.testing.assert_close(t.graph(size=8)["basecolor"][0, :, 0, 0], torch.tensor([0.75, 0.0, 0.25, 1.0]))
    # a value outside the declared range widens it
    t = translate(_write(tmp_path, _blend_doc(blend_params=[W.param("opacitymult", "constantValueFloat1", 40)])))
    assert t.graph.nodes["blend_1"].values()["opacitymult"].item() == pytest.approx(40)


def test_unknown_nodes_become_passthrough(tmp_path):
    nodes = [_uniform(10, "0.3 0.3 0.3 1", comptype=2),
             W.filter_node(20, "frobnicate", conns=[("input1", 10, 11)], outputs=[(21, 2)]),
             W.instance_node(30, "pkg:///no_such_generator?dependency=5", outputs=[(31, "output", 1)]),
             W.output_node(40, 100, 20, 21), W.output_node(41, 101, 30, 31)]
    doc = W.package([W.graph("P", nodes, outputs=[(100, "r", "roughness"), (101, "c", "baseColor")])],
                    dependencies=[(5, "sbs://nothing.sbs")])
    t = translate(_write(tmp_path, doc))
    assert t.report["unsupported"] == {"frobnicate": 1, "no_such_generator": 1}
    assert t.report["nodes_passthrough"] == 2
    out = t.graph(size=8)
    torch.testing.assert_close(out["roughness"], torch.full((1, 1, 8, 8), 0.3))  # its input, passed through
    torch.testing.assert_close(out["basecolor"][0, :, 0, 0], torch.tensor([0.5, 0.5, 0.5, 1.0]))  # gray


def test_an_unsupported_normal_generator_stands_in_as_a_flat_normal(tmp_path):
    nodes = [W.instance_node(30, "pkg:///grunge_normal_dents?dependency=5", outputs=[(31, "output", 1)]),
             W.instance_node(50, "pkg:///abnormal_grunge?dependency=5", outputs=[(51, "output", 1)]),
             W.output_node(40, 100, 30, 31), W.output_node(41, 101, 50, 51)]
    doc = W.package([W.graph("N", nodes, outputs=[(100, "normal", "normal"), (101, "c", "baseColor")])],
                    dependencies=[(5, "sbs://scratches.sbs")])
    out = translate(_write(tmp_path, doc)).graph(size=8)
    torch.testing.assert_close(out["normal"][0, :, 0, 0], torch.tensor([0.5, 0.5, 1.0, 1.0]))  # straight up
    torch.testing.assert_close(out["basecolor"][0, :, 0, 0], torch.tensor([0.5, 0.5, 0.5, 1.0]))  # "abnormal": grey


def _sub_graph():
    """A sub-graph: uniform of colour `tint` blended (copy) over nothing -> output."""
    color = W.dyn_param("outputcolor", 1, [W.fnode(1, "get_float4", data=("constantValueString", "tint"),
                                                   type_code=2048)])
    nodes = [W.filter_node(10, "uniform", params=[color], outputs=[(11, 1)]), W.output_node(20, 200, 10, 11)]
    return W.graph("Sub", nodes, outputs=[(200, "out", "baseColor")],
                   paraminputs=[W.paraminput("tint", 6, 2048, "constantValueFloat4", "0 1 0 1")])


def _instance_doc(dep_file="?himself", with_sub=True, tint=None, exposed=False):
    params = []
    if tint is not None:
        params.append(W.param("tint", "constantValueFloat4", tint))
    if exposed:
        params.append(W.dyn_param("tint", 1, [W.fnode(1, "get_float4", data=("constantValueString", "top"),
                                                      type_code=2048)]))
    nodes = [W.instance_node(10, "pkg:///Sub?dependency=9", params=params, outputs=[(11, "out", 1)]),
             W.output_node(20, 100, 10, 11)]
    pis = [W.paraminput("top", 7, 2048, "constantValueFloat4", "0.5 0.25 0 1")] if exposed else []
    graphs = [W.graph("Main", nodes, outputs=[(100, "basecolor", "baseColor")], paraminputs=pis)]
    if with_sub:
        graphs.append(_sub_graph())
    return W.package(graphs, dependencies=[(9, dep_file)])


def test_instances_of_the_same_package_are_inlined(tmp_path):
    t = translate(_write(tmp_path, _instance_doc()), graph_name="Main")
    assert t.report["subgraphs_inlined"] == 1
    torch.testing.assert_close(t.graph(size=8)["basecolor"][0, :, 0, 0], torch.tensor([0.0, 1.0, 0.0, 1.0]))
    t = translate(_write(tmp_path, _instance_doc(tint="1 0 0 1")), graph_name="Main")
    torch.testing.assert_close(t.graph(size=8)["basecolor"][0, :, 0, 0], torch.tensor([1.0, 0.0, 0.0, 1.0]))
    # the instance's value is a function of the top graph's exposed parameter: still bound through
    t = translate(_write(tmp_path, _instance_doc(exposed=True)), graph_name="Main", mode="exposed")
    g = t.graph
    torch.testing.assert_close(g(size=8)["basecolor"][0, :, 0, 0], torch.tensor([0.5, 0.25, 0.0, 1.0]))
    g.exposed.set_values(top=[0.0, 0.0, 1.0, 1.0])
    g.clear_cache()
    torch.testing.assert_close(g(size=8)["basecolor"][0, :, 0, 0], torch.tensor([0.0, 0.0, 1.0, 1.0]))


def test_local_dependency_file(tmp_path):
    _write(tmp_path, W.package([_sub_graph()]), "lib.sbs")
    t = translate(_write(tmp_path, _instance_doc("lib.sbs", with_sub=False)))
    torch.testing.assert_close(t.graph(size=8)["basecolor"][0, :, 0, 0], torch.tensor([0.0, 1.0, 0.0, 1.0]))
    with pytest.raises(TranslatorError, match="missing dependency"):
        translate(_write(tmp_path, _instance_doc("other.sbs", with_sub=False)))


@pytest.mark.skipif(not has_spec("clouds_2"), reason="clouds_2 not registered")
def test_library_instances_map_by_name_with_old_outputs_and_seeds(tmp_path):
    nodes = [W.instance_node(10, "pkg:///noise_clouds_2?dependency=3",
                             params=[W.param("randomseed", "constantValueInt32", 7)],
                             outputs=[(11, "Clouds_2", 2)]),
             W.output_node(20, 100, 10, 11)]
    doc = W.package([W.graph("C", nodes, outputs=[(100, "h", "height")])], dependencies=[(3, "sbs://noise_clouds_2.sbs")])
    t = translate(_write(tmp_path, doc))
    assert t.report["nodes_translated"] == 1 and not t.report["unsupported"]
    node = next(iter(t.graph.nodes.values()))
    assert node.spec.name == "clouds_2" and node.seed == 7
    assert t.graph(size=SIZE)["height"].shape == (1, 1, SIZE, SIZE)


def test_weave_scratches_normal_metal_and_tile_blending_translate_natively(tmp_path):
    """Library nodes of production materials: Weave 1 (its legacy output ``Weave``), the Scratches
    Generator's Normal version (two outputs), PBR Metal Reflectance, and the Tile Generator's
    Blending Mode (2 Max in every production file that sets it; Add when unset)."""
    nodes = [W.instance_node(10, "pkg:///weave_1?dependency=3", params=[W.param("Tiling", "constantValueInt32", 32)],
                             outputs=[(11, "Weave", 2)]),
             W.instance_node(12, "pkg:///scratches_generator_normal?dependency=4",
                             params=[W.param("spline_number", "constantValueInt32", 4096),
                                     W.param("normal_format", "constantValueInt32", 1)],
                             outputs=[(13, "normal", 1), (14, "mask", 2)]),
             W.instance_node(15, "pkg:///pbr_metal_reflectance?dependency=5",
                             params=[W.param("metal_color", "constantValueInt32", 4)], outputs=[(16, "output", 1)]),
             W.instance_node(17, "pkg:///tile_generator?dependency=6",
                             params=[W.param("BlendingMode", "constantValueInt32", 2),
                                     W.param("GlobalOpacity", "constantValueFloat1", 0.5)],
                             outputs=[(18, "output", 2)]),
             W.output_node(20, 100, 10, 11), W.output_node(21, 101, 12, 13), W.output_node(22, 102, 12, 14),
             W.output_node(23, 103, 15, 16), W.output_node(24, 104, 17, 18)]
    doc = W.package([W.graph("L", nodes, outputs=[(100, "h", "height"), (101, "n", "normal"),
                                                  (102, "r", "roughness"), (103, "c", "baseColor"),
                                                  (104, "m", "metallic")])],
                    dependencies=[(3, "sbs://weave_1.sbs"), (4, "sbs://pattern_scratches_generator.sbs"),
                                  (5, "sbs://pbr_metal_reflectance.sbs"), (6, "sbs://tile_generator.sbs")])
    t = translate(_write(tmp_path, doc))
    assert t.report["nodes_translated"] == 4 and not t.report["unsupported"] and not t.report["params_dropped"]
    by_spec = {n.spec.name: n for n in t.graph.nodes.values()}
    assert set(by_spec) == {"weave_1", "scratches_generator_normal", "pbr_metal_reflectance", "tile_generator"}
    assert by_spec["weave_1"].fixed["tiling"] == 32
    assert by_spec["scratches_generator_normal"].fixed["amount"] == 45   # 4096 scratches, two a cell
    assert by_spec["tile_generator"].fixed["blending_mode"] == 2
    out = t.graph(size=SIZE)
    assert out["normal"].shape[1] == 4 and out["roughness"].shape[1] == 1
    copper = out["basecolor"][0, :3, 0, 0]
    assert copper[0] > copper[1] > copper[2]


def test_output_size_inheritance(tmp_path):
    nodes = [W.filter_node(10, "uniform", params=[W.param("outputsize", "constantValueInt2", "6 6", 0)],
                           outputs=[(11, 1)]),
             W.filter_node(20, "passthrough", conns=[("input", 10, 11)], outputs=[(21, 1)]),
             W.filter_node(30, "uniform", params=[W.param("outputsize", "constantValueInt2", "-1 1", 1)],
                           outputs=[(31, 2)]),
             W.output_node(40, 100, 20, 21), W.output_node(41, 101, 30, 31)]
    doc = W.package([W.graph("S", nodes, outputs=[(100, "c", "baseColor"), (101, "r", "roughness")],
                              base_params=[W.param("outputsize", "constantValueInt2", "9 9", 0)])])
    r = translate(_write(tmp_path, doc)).report
    assert r["outputs"]["basecolor"]["size_log2"] == [6, 6]
    assert r["outputs"]["roughness"]["size_log2"] == [8, 10]


def test_pixel_and_value_processors(tmp_path):
    perpixel = W.dyn_param("perpixel", 3, [
        W.fnode(1, "get_float2", data=("constantValueString", "$pos"), type_code=512),
        W.fnode(2, "swizzle1", {"vector": 1}, data=("constantValueInt1", 0)),
        W.fnode(3, "mul", {"a": 2, "b": 4}),
        W.fnode(4, "get_float1", data=("constantValueString", "gain")),
    ])
    value = W.dyn_param("function", 1, [W.fnode(1, "const_float4", data=("constantValueFloat4", "0.5 0.5 0.5 1"),
                                                type_code=2048)])
    pin = W.dyn_param("outputcolor", 1, [W.fnode(1, "get_float4", data=("constantValueString", "#color"),
                                                 type_code=2048)])
    nodes = [W.filter_node(10, "pixelprocessor", params=[perpixel, W.param("colorswitch", "constantValueBool", 0)],
                           outputs=[(11, 2)]),
             W.filter_node(20, "valueprocessor", params=[value], outputs=[(21, 2048)]),
             W.filter_node(30, "uniform", params=[pin], conns=[("#color", 20, 21)], outputs=[(31, 1)]),
             W.output_node(40, 100, 10, 11), W.output_node(41, 101, 30, 31)]
    doc = W.package([W.graph("PP", nodes, outputs=[(100, "h", "height"), (101, "c", "baseColor")],
                             paraminputs=[W.paraminput("gain", 5, 256, "constantValueFloat1", 0.5)])])
    out = translate(_write(tmp_path, doc)).graph(size=8)
    torch.testing.assert_close(out["height"][0, 0, 0], 0.5 * (torch.arange(8) + 0.5) / 8)
    torch.testing.assert_close(out["basecolor"][0, :, 0, 0], torch.tensor([0.5, 0.5, 0.5, 1.0]))


def test_anisotropy_usages_map_to_the_anisotropy_outputs(tmp_path):
    """Outputs whose usage is anisotropyLevel / anisotropyAngle become the anisotropy level and
    angle maps, one channel each (a colour output is reduced to grey), which the renderer reads."""
    nodes = [_uniform(10, "0.5 0.5 0.5 1"), _uniform(20, "0.7 0.7 0.7 1", comptype=2),
             _uniform(30, "0.2 0.2 0.2 1"), W.output_node(40, 100, 10, 11), W.output_node(41, 101, 20, 21),
             W.output_node(42, 102, 30, 31)]
    doc = W.package([W.graph("Brushed", nodes, outputs=[(100, "basecolor", "baseColor"),
                                                        (101, "aniso", "anisotropyLevel"),
                                                        (102, "aniso_angle", "anisotropyAngle")])])
    out = translate(_write(tmp_path, doc)).graph(size=SIZE)
    assert set(out) == {"basecolor", "anisotropylevel", "anisotropyangle"}
    assert out["anisotropylevel"].shape == out["anisotropyangle"].shape == (1, 1, SIZE, SIZE)
    torch.testing.assert_close(out["anisotropylevel"][0, 0, 0, 0], torch.tensor(0.7))
    torch.testing.assert_close(out["anisotropyangle"][0, 0, 0, 0], torch.tensor(0.2))


def test_graph_selection(tmp_path):
    path = _write(tmp_path, _instance_doc())
    assert translate(path, graph_name="Sub").report["graph"] == "sub"
    with pytest.raises(TranslatorError, match="no graph named"):
        translate(path, graph_name="Nope")


def test_real_files_translate_and_evaluate(shared_dir):
    for f in sorted((shared_dir / "data" / "sbs").glob("*.sbs")):
        t = translate(f)
        r = t.report
        assert r["nodes_total"] == r["nodes_translated"] + r["nodes_passthrough"], f.name
        out = t.graph(size=SIZE)
        assert set(out) >= {"basecolor"}
        for image in out.values():
            assert torch.isfinite(image).all() and image.shape[-1] == SIZE


def test_every_unit_test_graph_translates(shared_dir):
    from blender_match.translator.parse import load_package
    path = shared_dir / "data" / "sbs" / "synthoid_UnitTests.sbs"
    for g in load_package(path).graphs:
        t = translate(path, graph_name=g.identifier)
        assert t.graph(size=16)["basecolor"].shape[-1] == 16
