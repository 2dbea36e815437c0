"""Hostile and broken documents: each gives a one-line TranslatorError naming the file, and
nothing else (no other exception, no entity expansion, no file or network access)."""
from __future__ import annotations

import pytest
import sbs_snippets as W
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from blender_match.translator import TranslatorError, translate


def _valid():
    nodes = [W.filter_node(10, "uniform", params=[W.param("outputcolor", "constantValueFloat4", "1 0 0 1")],
                           outputs=[(11, 1)]),
             W.filter_node(20, "levels", conns=[("input1", 10, 11)], outputs=[(21, 1)],
                           params=[W.param("levelinlow", "constantValueFloat4", "0.1 0.1 0.1 0")]),
             W.filter_node(30, "blend", conns=[("destination", 20, 21), ("source", 10, 11)], outputs=[(31, 1)],
                           params=[W.dyn_param("opacitymult", 3, [
                               W.fnode(1, "get_float1", data=("constantValueString", "amount")),
                               W.fnode(2, "const_float1", data=("constantValueFloat1", 0.5)),
                               W.fnode(3, "mul", {"a": 1, "b": 2})])]),
             W.output_node(40, 100, 30, 31)]
    return W.package([W.graph("G", nodes, outputs=[(100, "basecolor", "baseColor")],
                              paraminputs=[W.paraminput("amount", 5, 256, "constantValueFloat1", 0.8)])])


def _expect_error(tmp_path, text, match=None, name="bad.sbs", **kw):
    path = tmp_path / name
    path.write_bytes(text if isinstance(text, bytes) else text.encode())
    with pytest.raises(TranslatorError, match=match) as info:
        translate(path, **kw)
    message = str(info.value)
    assert "\n" not in message and name in message
    return message


def test_valid_document_translates(tmp_path):
    path = tmp_path / "ok.sbs"
    path.write_text(_valid())
    assert translate(path).graph(size=8)["basecolor"].shape == (1, 4, 8, 8)


def test_malformed_and_truncated(tmp_path):
    _expect_error(tmp_path, "<package><content><graph>", "malformed XML")
    _expect_error(tmp_path, _valid()[: len(_valid()) // 2], "malformed XML")
    _expect_error(tmp_path, b"", "empty")
    _expect_error(tmp_path, b"\xff\xfe\x00garbage", None)
    _expect_error(tmp_path, "<notapackage/>", "not a Substance package")
    _expect_error(tmp_path, "<package><content/></package>", "no graph")


def test_cycle_and_missing_node(tmp_path):
    cyc = _valid().replace('<identifier v="input1"/><connRef v="10"/>', '<identifier v="input1"/><connRef v="30"/>')
    _expect_error(tmp_path, cyc, "cycle")
    missing = _valid().replace('<connRef v="10"/>', '<connRef v="12345"/>', 1)
    _expect_error(tmp_path, missing, "missing node")
    dup = _valid().replace('<uid v="20"/>', '<uid v="10"/>')
    _expect_error(tmp_path, dup, "duplicate")


def test_missing_dependency_and_recursive_instancing(tmp_path):
    inst = W.instance_node(10, "pkg:///Lib?dependency=4", outputs=[(11, "out", 1)])
    doc = W.package([W.graph("G", [inst, W.output_node(20, 100, 10, 11)], outputs=[(100, "c", "baseColor")])],
                    dependencies=[(4, "../nowhere/lib.sbs")])
    _expect_error(tmp_path, doc, "missing dependency")
    selfref = W.instance_node(10, "pkg:///G?dependency=4", outputs=[(11, "c", 1)])
    doc = W.package([W.graph("G", [selfref, W.output_node(20, 100, 10, 11)], outputs=[(100, "c", "baseColor")])],
                    dependencies=[(4, "?himself")])
    _expect_error(tmp_path, doc, "instances itself")


def test_external_entities_are_refused(tmp_path):
    secret = tmp_path / "secret.txt"
    secret.write_text("TOP-SECRET")
    xxe = (f'<?xml version="1.0"?><!DOCTYPE package [<!ENTITY x SYSTEM "file://{secret}">]>'
           '<package><content><graph><identifier v="&x;"/></graph></content></package>')
    message = _expect_error(tmp_path, xxe, "not allowed")
    assert "TOP-SECRET" not in message


def test_billion_laughs_is_refused(tmp_path):
    lol = ['<!ENTITY lol0 "lol">'] + [f'<!ENTITY lol{i} "{("&lol%d;" % (i - 1)) * 10}">' for i in range(1, 10)]
    bomb = f'<?xml version="1.0"?><!DOCTYPE package [{"".join(lol)}]><package><identifier v="&lol9;"/></package>'
    _expect_error(tmp_path, bomb, "not allowed")
    # the same hidden in UTF-16
    _expect_error(tmp_path, bomb.replace('<?xml version="1.0"?>', "").encode("utf-16"), "not allowed")


def test_too_large(tmp_path):
    big = _valid().replace("<content>", "<content>" + "<group/>" * 5000)
    _expect_error(tmp_path, big, "too large", max_bytes=10_000)


def test_deeply_nested_document(tmp_path):
    deep = "<package>" + "<a>" * 5000 + "</a>" * 5000 + "</package>"
    _expect_error(tmp_path, deep)


_MUTATIONS = st.lists(st.tuples(st.sampled_from(["delete", "insert", "dup", "digit", "swap_tag"]),
                                st.integers(0, 10 ** 6), st.integers(1, 40),
                                st.sampled_from(["<", ">", "&", '"', "0", "-1", "1e308", "nan", "</compNode>",
                                                 "<compNode>", "<connRef v=\"30\"/>", "\x00", "]]>", "é"])),
                      min_size=1, max_size=4)


@settings(max_examples=100, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture,
                                                                   HealthCheck.too_slow])
@given(mutations=_MUTATIONS)
def test_fuzz_only_translator_errors(tmp_path, mutations):
    text = _valid()
    for kind, pos, length, token in mutations:
        pos %= len(text)
        if kind == "delete":
            text = text[:pos] + text[pos + length:]
        elif kind == "insert":
            text = text[:pos] + token + text[pos:]
        elif kind == "dup":
            text = text[:pos] + text[pos:pos + length * 10] + text[pos:]
        elif kind == "digit":
            text = "".join(ch if not ch.isdigit() or i < pos or i > pos + length else str((int(ch) + 3) % 10)
                           for i, ch in enumerate(text))
        else:
            text = text.replace("levels", token.strip("<>/") or "x", 1)
    path = tmp_path / "fuzz.sbs"
    path.write_bytes(text.encode("utf-8", "surrogatepass"))
    try:
        t = translate(path)
    except TranslatorError as exc:
        assert "\n" not in str(exc)
        return
    compile(t.program, "<generated>", "exec")
    t.graph(size=8)
