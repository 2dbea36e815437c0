"""Parsing .sbs documents into the translator's model (values, spellings, graphs, function graphs)."""
from __future__ import annotations

import pytest
import sbs_snippets as W

from blender_match.translator.parse import load_package
from blender_match.translator.values import BadValue, decode_text
from blender_match.translator.xml_safety import parse_bytes


def _pkg(text, tmp_path, name="doc.sbs"):
    path = tmp_path / name
    path.write_text(text)
    return load_package(path)


def test_decode_values():
    assert decode_text("float", 4, "0 0.5 0.5 1").value == (0.0, 0.5, 0.5, 1.0)
    assert decode_text("int", 2, "9 9").value == (9, 9)
    assert decode_text("int", 1, "4294967295").value == (-1,)  # stored unsigned
    assert decode_text("bool", 1, "1").value is True
    assert decode_text("string", 1, "pkg:///x").value == "pkg:///x"
    for kind, n, text in (("float", 1, "nan"), ("float", 2, "1"), ("int", 1, "x"), ("float", 1, "1e999")):
        with pytest.raises(BadValue):
            decode_text(kind, n, text)


def test_graph_structure(tmp_path):
    doc = W.package([W.graph("Mat", [
        W.filter_node(10, "uniform", params=[W.param("outputcolor", "constantValueFloat4", "1 0 0 1"),
                                             W.param("outputsize", "constantValueInt2", "8 8", 0)]),
        W.filter_node(20, "blend", conns=[("source", 10, 11), ("destination", 10)], outputs=[(21, 1)]),
        W.output_node(30, 99, 20, 21),
    ], outputs=[(99, "basecolor", "baseColor")],
        paraminputs=[W.paraminput("contrast", 5, 256, "constantValueFloat1", 0.25, 0, 2)])],
        dependencies=[(7, "?himself")])
    pkg = _pkg(doc, tmp_path)
    g = pkg.graphs[0]
    assert g.identifier == "Mat" and pkg.dependencies == {"7": "?himself"}
    assert g.outputs[0].usages == ["baseColor"]
    pi = g.paraminputs[0]
    assert (pi.identifier, pi.type, pi.default.value, pi.min, pi.max) == ("contrast", 256, (0.25,), 0.0, 2.0)
    u = g.nodes["10"]
    assert u.impl == "filter" and u.name == "uniform"
    assert u.params["outputcolor"].constant.value == (1.0, 0.0, 0.0, 1.0)
    assert u.params["outputsize"].relative_to == 0
    b = g.nodes["20"]
    assert [(c.identifier, c.source, c.source_output) for c in b.connections] == [
        ("source", "10", "11"), ("destination", "10", None)]
    assert g.nodes["30"].impl == "output" and g.nodes["30"].ref == "99"


def test_old_spellings(tmp_path):
    doc = ('<package><content><graph><identifier><value v="Old"/></identifier><uid v="1"/><compNodes>'
           '<compNode><uid><value v="5"/></uid><compImplementation><compFilter><filter><value v="uniform"/></filter>'
           '<parameters><parameter><name v="outputcolor"/><paramValue><constantValueFloat4><value v="0 1 0 1"/>'
           '</constantValueFloat4></paramValue></parameter></parameters></compFilter></compImplementation></compNode>'
           '<compNode><uid v="6"/><connexions><connexion><identifier v="input1"/><connRef><value v="5"/></connRef>'
           '</connexion></connexions><compImplementation><compFilter><filter v="levels"/></compFilter>'
           '</compImplementation></compNode></compNodes></graph></content></package>')
    g = _pkg(doc, tmp_path).graphs[0]
    assert g.identifier == "Old"
    assert g.nodes["5"].params["outputcolor"].constant.value == (0.0, 1.0, 0.0, 1.0)
    assert g.nodes["6"].connections[0].source == "5"


def test_dynamic_values(tmp_path):
    fn = W.dyn_param("opacitymult", 3, [
        W.fnode(1, "get_float1", data=("constantValueString", "contrast")),
        W.fnode(2, "const_float1", data=("constantValueFloat1", 0.5)),
        W.fnode(3, "mul", {"a": 1, "b": 2}),
    ])
    bad = W.dyn_param("opacity", 1, [W.fnode(1, "instance", data=("constantValueString", "pkg:///f"))])
    doc = W.package([W.graph("G", [W.filter_node(10, "blend", params=[fn, bad])])])
    node = _pkg(doc, tmp_path).graphs[0].nodes["10"]
    g = node.params["opacitymult"].dynamic
    assert g["nodes"][g["root"]]["function"] == "mul"
    assert {n.get("data") for n in g["nodes"].values()} >= {"contrast", 0.5}
    assert "unsupported function 'instance'" in node.params["opacity"].error


def test_groups_and_graph_paths(tmp_path):
    inner = W.graph("Inner", [])
    doc = W.package([]).replace("<content></content>",
                                "<content><group><identifier v='Resources'/>"
                                f"<content>{inner}</content></group></content>")
    pkg = _pkg(doc, tmp_path)
    assert pkg.find_graph("Resources/Inner").identifier == "Inner"
    assert pkg.find_graph("inner") is not None


def test_real_files_parse(shared_dir):
    files = sorted((shared_dir / "data" / "sbs").glob("*.sbs"))
    assert len(files) == 6
    for f in files:
        pkg = load_package(f)
        assert pkg.graphs, f
        assert any(g.outputs for g in pkg.graphs)
    unit = load_package(shared_dir / "data" / "sbs" / "synthoid_UnitTests.sbs")
    assert len(unit.graphs) > 10


def test_parse_bytes_rejects_non_package():
    from blender_match.translator import TranslatorError
    with pytest.raises(TranslatorError):
        parse_bytes(b"<html/>", "x.sbs")
