"""Writing small .sbs documents by hand for the translator tests: each helper returns XML text
with every value escaped. Covers the constructs the translator reads; not a general writer."""
from __future__ import annotations

import zlib
from xml.sax.saxutils import quoteattr

TAGS = {1: "constantValueFloat1", 2: "constantValueFloat2", 3: "constantValueFloat3", 4: "constantValueFloat4"}


def v(tag: str, value) -> str:
    return f"<{tag} v={quoteattr(str(value))}/>"


def const(tag: str, value) -> str:
    """A constant value element: ``const("constantValueFloat4", "1 0 0 1")``."""
    if isinstance(value, (list, tuple)):
        value = " ".join(str(x) for x in value)
    return v(tag, value)


def param(name: str, tag: str, value, relative_to: int | None = None) -> str:
    rel = v("relativeTo", relative_to) if relative_to is not None else ""
    return f"<parameter>{v('name', name)}{rel}<paramValue>{const(tag, value)}</paramValue></parameter>"


def fnode(uid, function: str, conns: dict | None = None, data: tuple | None = None, type_code: int = 256) -> str:
    """A function-graph node; ``data`` = (tag, value) stored in a funcData named like the function."""
    c = "".join(f"<connection>{v('identifier', p)}{v('connRef', s)}</connection>" for p, s in (conns or {}).items())
    c = f"<connections>{c}</connections>" if c else ""
    d = ""
    if data is not None:
        d = (f"<funcDatas><funcData>{v('name', function)}<constantValue>{const(*data)}</constantValue>"
             f"</funcData></funcDatas>")
    return f"<paramNode>{v('uid', uid)}{v('function', function)}{v('type', type_code)}{c}{d}</paramNode>"


def dynamic(root, nodes: list[str]) -> str:
    return f"<dynamicValue>{v('rootnode', root)}<paramNodes>{''.join(nodes)}</paramNodes></dynamicValue>"


def dyn_param(name: str, root, nodes: list[str], relative_to: int | None = None) -> str:
    rel = v("relativeTo", relative_to) if relative_to is not None else ""
    return f"<parameter>{v('name', name)}{rel}<paramValue>{dynamic(root, nodes)}</paramValue></parameter>"


def _conns(conns) -> str:
    out = []
    for c in conns:
        ident, src = c[0], c[1]
        o = v("connRefOutput", c[2]) if len(c) > 2 and c[2] is not None else ""
        out.append(f"<connection>{v('identifier', ident)}{v('connRef', src)}{o}</connection>")
    return f"<connections>{''.join(out)}</connections>" if out else ""


def _outputs(outputs) -> str:
    if not outputs:
        return ""
    return "<compOutputs>" + "".join(
        f"<compOutput>{v('uid', u)}{v('comptype', ct)}</compOutput>" for u, ct in outputs) + "</compOutputs>"


def filter_node(uid, name: str, *, params=(), conns=(), outputs=None, arrays: str = "") -> str:
    """An atomic node; ``outputs`` = [(uid, comptype)] (default one colour output uid+1)."""
    outputs = [(int(uid) + 1, 1)] if outputs is None else outputs
    return (f"<compNode>{v('uid', uid)}{_outputs(outputs)}{_conns(conns)}<compImplementation><compFilter>"
            f"{v('filter', name)}<parameters>{''.join(params)}</parameters>{arrays}</compFilter>"
            f"</compImplementation></compNode>")


def instance_node(uid, path: str, *, params=(), conns=(), outputs=()) -> str:
    """An instance; ``outputs`` = [(uid, identifier, comptype)]."""
    bridg = "".join(f"<outputBridging>{v('uid', u)}{v('identifier', i)}</outputBridging>" for u, i, _ in outputs)
    return (f"<compNode>{v('uid', uid)}{_outputs([(u, ct) for u, _, ct in outputs])}{_conns(conns)}"
            f"<compImplementation><compInstance>{v('path', path)}<parameters>{''.join(params)}</parameters>"
            f"<outputBridgings>{bridg}</outputBridgings></compInstance></compImplementation></compNode>")


def input_node(uid, entry, out_uid, comptype: int = 1) -> str:
    return (f"<compNode>{v('uid', uid)}{_outputs([(out_uid, comptype)])}<compImplementation><compInputBridge>"
            f"{v('entry', entry)}</compInputBridge></compImplementation></compNode>")


def output_node(uid, graphoutput, source, source_output=None) -> str:
    return (f"<compNode>{v('uid', uid)}{_conns([('inputNodeOutput', source, source_output)])}"
            f"<compImplementation><compOutputBridge>{v('output', graphoutput)}</compOutputBridge>"
            f"</compImplementation></compNode>")


def paraminput(identifier: str, uid, type_code: int, default_tag: str | None = None, default=None,
               lo=None, hi=None) -> str:
    d = f"<defaultValue>{const(default_tag, default)}</defaultValue>" if default_tag else ""
    opts = "".join(f"<option>{v('name', n)}{v('value', x)}</option>" for n, x in (("min", lo), ("max", hi))
                   if x is not None)
    w = f"<defaultWidget>{v('name', 'slider')}<options>{opts}</options></defaultWidget>" if opts else ""
    return (f"<paraminput>{v('identifier', identifier)}{v('uid', uid)}{v('type', type_code)}{d}{w}"
            f"</paraminput>")


def graph(identifier: str, nodes: list[str], outputs=(), paraminputs=(), base_params=()) -> str:
    """A graph; ``outputs`` = [(graphoutput uid, identifier, usage)]."""
    outs = "".join(f"<graphoutput>{v('identifier', i)}{v('uid', u)}<usages><usage>{v('components', 'RGBA')}"
                   f"{v('name', usage)}</usage></usages></graphoutput>" for u, i, usage in outputs)
    return (f"<graph>{v('identifier', identifier)}{v('uid', zlib.crc32(identifier.encode()) % 10 ** 9)}"
            f"<paraminputs>{''.join(paraminputs)}</paraminputs><graphOutputs>{outs}</graphOutputs>"
            f"<compNodes>{''.join(nodes)}</compNodes><baseParameters>{''.join(base_params)}</baseParameters>"
            f"</graph>")


def package(graphs: list[str], dependencies=()) -> str:
    """A package; ``dependencies`` = [(uid, filename)]."""
    deps = "".join(f"<dependency>{v('filename', f)}{v('uid', u)}{v('type', 'package')}</dependency>"
                   for u, f in dependencies)
    return (f'<?xml version="1.0" encoding="UTF-8"?><package>{v("identifier", "test")}'
            f"{v('formatVersion', '1.1.0.202302')}<dependencies>{deps}</dependencies>"
            f"<content>{''.join(graphs)}</content></package>")


def white_noise_package(identifier: str = "Grain") -> str:
    """A package of one graph whose base colour is Substance's White Noise: a grain a pixel wide
    at every output size, so the graph looks different rendered at 128 px than at 512 brought
    down (``selection.bank.measured_supersample``)."""
    nodes = [instance_node(10, "pkg:///white_noise?dependency=5", outputs=[(11, "output", 1)]),
             output_node(20, 100, 10, 11)]
    return package([graph(identifier, nodes, outputs=[(100, "basecolor", "baseColor")])],
                   dependencies=[(5, "sbs://white_noise.sbs")])
