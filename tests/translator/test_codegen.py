"""Program generation: the generated module rebuilds the same graph; no text from the file can
inject code; the ``blender-match translate`` command."""
from __future__ import annotations

import importlib.util
import json

import sbs_snippets as W
import torch

from blender_match.cli import main
from blender_match.translator import translate

SIZE = 32


def _import(path, name="generated_graph"):
    spec = importlib.util.spec_from_file_location(name, path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _round_trip(t, tmp_path, size=SIZE):
    path = tmp_path / "prog.py"
    path.write_text(t.program)
    rebuilt = _import(path).build()
    direct = t.graph(size=size)
    again = rebuilt(size=size)
    assert set(direct) == set(again)
    for k in direct:
        torch.testing.assert_close(again[k], direct[k], msg=k)
    assert rebuilt.param_names() == t.graph.param_names()
    torch.testing.assert_close(rebuilt.get_vector(), t.graph.get_vector())
    return rebuilt


def _doc():
    color = W.dyn_param("outputcolor", 3, [
        W.fnode(1, "get_float4", data=("constantValueString", "tint"), type_code=2048),
        W.fnode(2, "const_float4", data=("constantValueFloat4", "0.5 0.5 0.5 1"), type_code=2048),
        W.fnode(3, "mul", {"a": 1, "b": 2}, type_code=2048),
    ])
    nodes = [W.filter_node(10, "uniform", params=[color], outputs=[(11, 1)]),
             W.filter_node(20, "uniform", params=[W.param("colorswitch", "constantValueBool", 0),
                                                  W.param("outputcolor", "constantValueFloat4", "0.7 0 0 1")],
                           outputs=[(21, 2)]),
             W.filter_node(30, "unknown_thing", conns=[("input1", 20, 21)], outputs=[(31, 2)]),
             W.output_node(40, 100, 10, 11), W.output_node(41, 101, 30, 31)]
    return W.package([W.graph("Mat", nodes, outputs=[(100, "basecolor", "baseColor"), (101, "r", "roughness")],
                              paraminputs=[W.paraminput("tint", 5, 2048, "constantValueFloat4", "1 0.5 0.25 1")])])


def test_round_trip_hand_written(tmp_path):
    src = tmp_path / "m.sbs"
    src.write_text(_doc())
    for mode in ("exposed", "exposed_plus", "all"):
        t = translate(src, mode=mode)
        assert "graph.add(" in t.program
        rebuilt = _round_trip(t, tmp_path)
        assert rebuilt.mode == mode


def test_round_trip_real_files(shared_dir, tmp_path):
    for f in sorted((shared_dir / "data" / "sbs").glob("*.sbs"))[:3]:
        _round_trip(translate(f), tmp_path, size=16)


def test_file_text_cannot_inject_code(tmp_path):
    evil = 'x"); import os; os.system("echo pwned") #'
    color = W.dyn_param("outputcolor", 1, [W.fnode(1, "get_float4", data=("constantValueString", evil),
                                                   type_code=2048)])
    label = W.dyn_param("text", 1, [W.fnode(1, "const_string", data=("constantValueString", evil),
                                            type_code=16384)])
    nodes = [W.filter_node(10, "uniform", params=[color], outputs=[(11, 1)]),
             W.filter_node(12, evil, conns=[("input1", 10, 11)], outputs=[(13, 1)]),
             W.filter_node(14, "text", params=[label, W.param("fontdata", "constantValueString", evil)],
                           conns=[("background", 12, 13)], outputs=[(15, 1)]),
             W.instance_node(20, f"pkg:///{evil}?dependency=1", conns=[(evil, 14, 15)], outputs=[(21, evil, 1)]),
             W.output_node(30, 100, 20, 21)]
    doc = W.package([W.graph(evil, nodes, outputs=[(100, evil, "baseColor")],
                             paraminputs=[W.paraminput(evil, 5, 2048, "constantValueFloat4", "1 1 1 1"),
                                          W.paraminput("s", 6, 16384, "constantValueString", evil)])],
                    dependencies=[(1, "sbs://" + evil)])
    src = tmp_path / "evil.sbs"
    src.write_text(doc)
    t = translate(src)
    assert "pwned" not in t.program and "import os" not in t.program
    _round_trip(t, tmp_path, size=8)


def test_cli_translate(tmp_path, capsys):
    src = tmp_path / "m.sbs"
    src.write_text(_doc())
    out, report = tmp_path / "out", tmp_path / "rep" / "r.json"
    assert main(["translate", str(src), "--out", str(out), "--report", str(report), "--mode", "exposed"]) == 0
    line = capsys.readouterr().out.strip()
    assert "\n" not in line and "nodes translated" in line
    data = json.loads(report.read_text())
    for key in ("nodes_total", "nodes_translated", "nodes_passthrough", "nodes_pruned", "unsupported",
                "params_optimizable", "outputs", "seconds"):
        assert key in data
    assert data["unsupported"] == {"unknown_thing": 1} and data["params_optimizable"] == 4
    assert (out / "mat.py").is_file()
    bad = tmp_path / "bad.sbs"
    bad.write_text("<package><content>")
    assert main(["translate", str(bad), "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.startswith("blender-match: error:") and "bad.sbs" in err and err.count("\n") == 1
