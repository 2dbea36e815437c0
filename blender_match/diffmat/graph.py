"""MaterialGraph: the runtime that holds nodes, their connections and the named material
outputs, and evaluates them (the MATch paper's DiffMatGraphModule, built by composition rather
than by subclassing, so the translator and hand-written graphs share one class).

The optimisable parameters of the whole graph form one vector in normalised space, in a fixed
order (nodes in insertion order, then each node's parameters in spec order); ``get_vector`` /
``set_vector`` read and write it, ``freeze`` / ``unfreeze`` pick which groups it holds, and a
forward pass with ``theta`` of shape (B, P) evaluates B parameter vectors at once.

Nodes whose value cannot change (no trainable parameter above them: generators with fixed
parameters, mostly) are computed once per size, seed and device and cached, which is what the
paper's precomputed generator inputs achieve, without precomputing anything by hand.

What ``forward`` needs from the graph's structure (evaluation order, each input's source and output
index, when a value can be freed, static nodes, parameter slots) is an ``EvalPlan`` computed once
and kept until the graph changes: every mutating method drops it (``_changed``), and a plan also
records which parameters required gradients, so toggling ``requires_grad`` by hand rebuilds it.
"""
from __future__ import annotations

import fnmatch
import re
from dataclasses import dataclass

import torch
from torch import nn

from ..vocabulary import CALIBRATION, USAGES
from .calibration import PhotoCalibration
from .errors import DiffMatError
from .nodes.module import EvalContext, Node, ParameterSet
from .toposort import topological_order

_NAME = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$")

Ref = tuple[str, str]  # (node, output name)
Slot = tuple[str, str, int]  # (owner, parameter, components)


@dataclass(frozen=True)
class Step:
    """One node's evaluation: its input sources as (node, output index) (None: not connected),
    and the values that can be freed after it (their last consumer)."""

    name: str
    args: tuple[tuple[str, int] | None, ...]
    frees: tuple[str, ...]


@dataclass(frozen=True)
class EvalPlan:
    """Everything ``forward`` needs that only changes when the graph does (see the module doc).

    ``static``: nodes whose value cannot change (no trainable parameter above them);
    ``cached``: the static ones whose value a non-static node or an output reads, so caching them
    is enough; ``grad_flags``: the ``requires_grad`` state the plan was made for."""

    steps: tuple[Step, ...]
    outputs: tuple[tuple[str, str, int], ...]  # (usage, node, output index)
    static: frozenset[str]
    cached: frozenset[str]
    slots: tuple[Slot, ...]
    num_params: int
    grad_flags: tuple[bool, ...]

    @property
    def order(self) -> list[str]:
        return [step.name for step in self.steps]


class MaterialGraph(nn.Module):
    """A directed acyclic graph of Nodes with named outputs (see ``USAGES``)."""

    def __init__(self, name: str = "graph"):
        super().__init__()
        self.name = name
        self.nodes = nn.ModuleDict()
        self.links: dict[str, list[tuple[str, str] | None]] = {}
        self.outputs: dict[str, Ref] = {}
        self._cache: dict[tuple, tuple[torch.Tensor, ...]] = {}
        self._plan: EvalPlan | None = None
        self.calibration = PhotoCalibration()

    # ---- building -------------------------------------------------------------------------
    def add(self, name: str, node: Node | str, inputs: dict | None = None, *, seed: int = 0,
            **params) -> str:
        """Add a node (a Node, or a registered node name with ``params``) and connect its inputs.

        ``inputs`` maps the node's input slot names to sources: "node" or "node:output".
        Returns ``name`` so graph code can chain.
        """
        if not _NAME.match(name):
            raise DiffMatError(f"graph {self.name}: node name {name!r} is not an identifier")
        if name == CALIBRATION:
            raise DiffMatError(f"graph {self.name}: node name {name!r} is reserved for the graph's calibration")
        if name in self.nodes:
            raise DiffMatError(f"graph {self.name}: node {name!r} already exists")
        if isinstance(node, str):
            node = Node(node, params, seed=seed)
        elif params:
            raise DiffMatError(f"graph {self.name}: pass parameters to Node() or by node name, not both")
        self.nodes[name] = node
        self.links[name] = [None] * len(node.spec.inputs)
        for slot, source in (inputs or {}).items():
            self.connect(source, name, slot)
        self._changed()
        return name

    def node(self, name: str) -> Node:
        """Node ``name`` (typed: ``nodes`` is an ``nn.ModuleDict``)."""
        node = self.nodes[name]
        assert isinstance(node, Node)
        return node

    def node_items(self) -> list[tuple[str, Node]]:
        """(name, Node) of every node, in insertion order."""
        return [(n, self.node(n)) for n in self.nodes]

    def _ref(self, source: str | tuple) -> Ref:
        if isinstance(source, str):
            node, _, output = source.partition(":")
        else:
            node, output = source[0], source[1]
        if node not in self.nodes:
            raise DiffMatError(f"graph {self.name}: connection from missing node {node!r}")
        outputs = self.node(node).spec.outputs
        output = output or outputs[0]
        if output not in outputs:
            raise DiffMatError(f"graph {self.name}: node {node!r} has no output {output!r} (has {list(outputs)})")
        return node, output

    def connect(self, source: str | tuple, target: str, slot: str):
        """Connect ``source`` ("node" or "node:output") to input ``slot`` of node ``target``."""
        if target not in self.nodes:
            raise DiffMatError(f"graph {self.name}: connection to missing node {target!r}")
        names = [i.name for i in self.node(target).spec.inputs]
        if slot not in names:
            raise DiffMatError(f"graph {self.name}: node {target!r} ({self.node(target).spec.name}) "
                               f"has no input {slot!r} (has {names})")
        self.links[target][names.index(slot)] = self._ref(source)
        self._changed()

    def set_output(self, usage: str, source: str | tuple):
        """Name a node output as one of the material maps (``USAGES``)."""
        if usage not in USAGES:
            raise DiffMatError(f"graph {self.name}: unknown output usage {usage!r}; expected one of {list(USAGES)}")
        self.outputs[usage] = self._ref(source)
        self._changed()

    def _changed(self):
        """Drop the evaluation plan and the cached values: the graph (or what may train) changed."""
        self._plan = None
        self._cache.clear()

    # ---- analysis ---------------------------------------------------------------------------
    def order(self) -> list[str]:
        """Nodes that reach an output, in topological order; DiffMatError on a cycle."""
        return self.plan().order

    def _sort(self) -> list[str]:
        needed: set[str] = set()
        stack = [n for n, _ in self.outputs.values()]
        while stack:
            n = stack.pop()
            if n not in needed:
                needed.add(n)
                stack.extend(src for src, _ in filter(None, self.links[n]))
        edges = {n: [src for src, _ in filter(None, self.links[n])] for n in self.nodes if n in needed}
        out, stuck = topological_order(edges)
        if stuck:
            raise DiffMatError(f"graph {self.name}: cycle through nodes {stuck[:5]}")
        return out

    def prune(self) -> list[str]:
        """Remove nodes that reach no output (data-flow analysis); returns their names."""
        keep = set(self.order())
        dead = [n for n in self.nodes if n not in keep]
        for n in dead:
            del self.nodes[n]
            del self.links[n]
        self._changed()
        return dead

    # ---- parameters -------------------------------------------------------------------------
    def parameter_sets(self) -> dict[str, ParameterSet]:
        """Every holder of parameters by name: the nodes and the photometric ``calibration`` (a
        subclass may add graph-level sets)."""
        return {**dict(self.node_items()), CALIBRATION: self.calibration}

    def may_train(self, owner: str, param: str) -> bool:
        """Whether ``owner.param`` may be optimised (a subclass may pin more, e.g. bound ones)."""
        return self.parameter_sets()[owner].optimizable(param)

    def param_slots(self) -> list[tuple[str, str, int]]:
        """(owner, parameter, components) of every trainable parameter, in vector order."""
        return [(n, p, t.numel()) for n, ps in self.parameter_sets().items()
                for p, t in ps.theta.items() if t.requires_grad]

    def param_names(self) -> list[str]:
        """One name per vector component: "node.param" or "node.param[i]"."""
        return [f"{n}.{p}" if k == 1 else f"{n}.{p}[{i}]"
                for n, p, k in self.param_slots() for i in range(k)]

    def num_params(self) -> int:
        return sum(k for _, _, k in self.param_slots())

    def get_vector(self) -> torch.Tensor:
        """The trainable parameters as one normalised vector (a detached copy)."""
        sets = self.parameter_sets()
        slots = self.param_slots()
        if not slots:
            return torch.zeros(0)
        return torch.cat([sets[n].theta[p].detach().reshape(-1) for n, p, _ in slots])

    def set_vector(self, vector: torch.Tensor):
        """Write a normalised vector (as from ``get_vector``) back into the parameters."""
        if vector.numel() != self.num_params():
            raise DiffMatError(f"graph {self.name}: parameter vector has {vector.numel()} values, "
                               f"expected {self.num_params()}")
        sets = self.parameter_sets()
        with torch.no_grad():
            i = 0
            for n, p, k in self.param_slots():
                t = sets[n].theta[p]
                t.copy_(vector[i:i + k].reshape(t.shape).to(t))
                i += k

    def _select(self, pattern: str, trainable: bool):
        hits = 0
        for n, ps in self.parameter_sets().items():
            for p, t in ps.theta.items():
                if fnmatch.fnmatchcase(f"{n}.{p}", pattern) or fnmatch.fnmatchcase(n, pattern):
                    t.requires_grad_(trainable and self.may_train(n, p))
                    hits += 1
        if not hits:
            raise DiffMatError(f"graph {self.name}: no parameter matches {pattern!r}")
        self._changed()

    def freeze(self, pattern: str = "*"):
        """Stop optimising parameters whose "owner.param" (or owner name) matches ``pattern``."""
        self._select(pattern, False)

    def unfreeze(self, pattern: str = "*"):
        """Optimise again the (optimisable) parameters matching ``pattern``."""
        self._select(pattern, True)

    def _split(self, theta: torch.Tensor, plan: EvalPlan) -> dict[str, dict[str, torch.Tensor]]:
        if theta.dim() != 2 or theta.shape[1] != plan.num_params:
            raise DiffMatError(f"graph {self.name}: theta must be (B, {plan.num_params}), got {tuple(theta.shape)}")
        out: dict[str, dict[str, torch.Tensor]] = {}
        i = 0
        for n, p, k in plan.slots:
            out.setdefault(n, {})[p] = theta[:, i:i + k]
            i += k
        return out

    # ---- the evaluation plan -----------------------------------------------------------------
    def _grad_flags(self) -> tuple[bool, ...]:
        return tuple(t.requires_grad for ps in self.parameter_sets().values() for t in ps.theta.values())

    def plan(self) -> EvalPlan:
        """The current evaluation plan, built on first use after a change (see the module doc)."""
        flags = self._grad_flags()
        if self._plan is None or self._plan.grad_flags != flags:
            self._plan = self._make_plan(flags)
        return self._plan

    def _make_plan(self, grad_flags: tuple[bool, ...]) -> EvalPlan:
        order = self._sort()
        static = self._static(order)
        outputs = tuple((u, n, self._output_index(n, o)) for u, (n, o) in self.outputs.items())
        slots = tuple(self.param_slots())
        return EvalPlan(steps=self._steps(order), outputs=outputs, static=frozenset(static),
                        cached=frozenset(static & self._read_by_dynamic(order, static)), slots=slots,
                        num_params=sum(k for _, _, k in slots), grad_flags=grad_flags)

    def _output_index(self, node: str, output: str) -> int:
        return self.node(node).spec.outputs.index(output)

    def _steps(self, order: list[str]) -> tuple[Step, ...]:
        """Each node's step; a value is freed after its last consumer, never when it is an output."""
        last_reader: dict[str, str] = {}
        for n in order:
            for src, _ in filter(None, self.links[n]):
                last_reader[src] = n
        for n, _ in self.outputs.values():
            last_reader.pop(n, None)
        frees: dict[str, list[str]] = {n: [] for n in order}
        for src, reader in last_reader.items():
            frees[reader].append(src)
        return tuple(Step(n, tuple(None if ref is None else (ref[0], self._output_index(*ref))
                                   for ref in self.links[n]), tuple(frees[n]))
                     for n in order)

    def _read_by_dynamic(self, order: list[str], static: set[str]) -> set[str]:
        """The nodes whose value an output or a non-static node reads."""
        readers = {n for n, _ in self.outputs.values()}
        for n in order:
            if n not in static:
                readers.update(src for src, _ in filter(None, self.links[n]))
        return readers

    def _dynamic(self) -> set[str]:
        """Nodes whose value depends on the parameter vector on their own (a subclass may add some)."""
        return {n for n, node in self.node_items() if any(t.requires_grad for t in node.theta.values())}

    def _static(self, order: list[str]) -> set[str]:
        dynamic = self._dynamic()
        static: set[str] = set()
        for n in order:
            if n not in dynamic and all(src in static for src, _ in filter(None, self.links[n])):
                static.add(n)
        return static

    # ---- evaluation --------------------------------------------------------------------------
    def forward(self, size: int = 512, seed: int = 0, theta: torch.Tensor | None = None,
                cache: bool = True) -> dict[str, torch.Tensor]:
        """Evaluate the graph at ``size`` pixels with graph seed ``seed``.

        ``theta`` (B, P) evaluates a batch of normalised parameter vectors. Returns the named
        outputs; their batch is B (or 1 when nothing varies in the batch). The ``basecolor`` output
        carries the photometric calibration's gain (``diffmat.calibration``; none by default).
        """
        if not self.outputs:
            raise DiffMatError(f"graph {self.name}: no outputs set")
        plan = self.plan()
        device = next((t.device for t in self.parameters()), torch.device("cpu"))
        dtype = next((t.dtype for t in self.parameters()), torch.float32)
        ctx = EvalContext(size=size, seed=seed, device=device, dtype=dtype)
        overrides = self._split(theta, plan) if theta is not None else {}
        static = plan.static if cache else frozenset()
        values: dict[str, tuple] = {}
        for step in plan.steps:
            n = step.name
            key = (n, size, seed, str(device), dtype)
            if n in static and key in self._cache:
                result = self._cache[key]
            else:
                args = [None if ref is None else values[ref[0]][ref[1]] for ref in step.args]
                result = self.node(n)(*args, ctx=ctx, override=overrides.get(n))
                result = result if isinstance(result, tuple) else (result,)
                if n in static and n in plan.cached:
                    result = self._cache[key] = tuple(r.detach() for r in result)
            values[n] = result
            for src in step.frees:
                del values[src]
        out = {u: values[n][i] for u, n, i in plan.outputs}
        if "basecolor" in out:
            out["basecolor"] = self.calibration.apply_gain(out["basecolor"])
        return out

    def clear_cache(self):
        """Drop cached outputs (after changing frozen parameters by hand)."""
        self._cache.clear()

    def _apply(self, fn, *args, **kwargs):
        self._changed()
        return super()._apply(fn, *args, **kwargs)
