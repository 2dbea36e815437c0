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
"""
from __future__ import annotations

import fnmatch
import re

import torch
from torch import nn

from .errors import DiffMatError
from .nodes.module import EvalContext, Node, ParameterSet
from .toposort import topological_order

USAGES = ("basecolor", "normal", "roughness", "metallic", "height", "ambientocclusion")
_NAME = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$")


class MaterialGraph(nn.Module):
    """A directed acyclic graph of Nodes with named outputs (see ``USAGES``)."""

    def __init__(self, name: str = "graph"):
        super().__init__()
        self.name = name
        self.nodes = nn.ModuleDict()
        self.links: dict[str, list[tuple[str, str] | None]] = {}
        self.outputs: dict[str, tuple[str, str]] = {}
        self._cache: dict[tuple, torch.Tensor] = {}

    # ---- building -------------------------------------------------------------------------
    def add(self, name: str, node: Node | str, inputs: dict | None = None, *, seed: int = 0,
            **params) -> str:
        """Add a node (a Node, or a registered node name with ``params``) and connect its inputs.

        ``inputs`` maps the node's input slot names to sources: "node" or "node:output".
        Returns ``name`` so graph code can chain.
        """
        if not _NAME.match(name):
            raise DiffMatError(f"graph {self.name}: node name {name!r} is not an identifier")
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
        self._cache.clear()
        return name

    def _ref(self, source: str | tuple) -> tuple[str, str]:
        node, _, output = source.partition(":") if isinstance(source, str) else (source[0], None, source[1])
        if node not in self.nodes:
            raise DiffMatError(f"graph {self.name}: connection from missing node {node!r}")
        outputs = self.nodes[node].spec.outputs
        output = output or outputs[0]
        if output not in outputs:
            raise DiffMatError(f"graph {self.name}: node {node!r} has no output {output!r} (has {list(outputs)})")
        return node, output

    def connect(self, source: str | tuple, target: str, slot: str):
        """Connect ``source`` ("node" or "node:output") to input ``slot`` of node ``target``."""
        if target not in self.nodes:
            raise DiffMatError(f"graph {self.name}: connection to missing node {target!r}")
        names = [i.name for i in self.nodes[target].spec.inputs]
        if slot not in names:
            raise DiffMatError(f"graph {self.name}: node {target!r} ({self.nodes[target].spec.name}) "
                               f"has no input {slot!r} (has {names})")
        self.links[target][names.index(slot)] = self._ref(source)
        self._cache.clear()

    def set_output(self, usage: str, source: str | tuple):
        """Name a node output as one of the material maps (``USAGES``)."""
        if usage not in USAGES:
            raise DiffMatError(f"graph {self.name}: unknown output usage {usage!r}; expected one of {list(USAGES)}")
        self.outputs[usage] = self._ref(source)

    # ---- analysis ---------------------------------------------------------------------------
    def order(self) -> list[str]:
        """Nodes that reach an output, in topological order; DiffMatError on a cycle."""
        needed, stack = set(), [n for n, _ in self.outputs.values()]
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
        self._cache.clear()
        return dead

    # ---- parameters -------------------------------------------------------------------------
    def parameter_sets(self) -> dict[str, ParameterSet]:
        """Every holder of parameters by name: the nodes (a subclass may add graph-level sets)."""
        return dict(self.nodes.items())

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
        self._cache.clear()

    def freeze(self, pattern: str = "*"):
        """Stop optimising parameters whose "owner.param" (or owner name) matches ``pattern``."""
        self._select(pattern, False)

    def unfreeze(self, pattern: str = "*"):
        """Optimise again the (optimisable) parameters matching ``pattern``."""
        self._select(pattern, True)

    def _split(self, theta: torch.Tensor) -> dict[str, dict[str, torch.Tensor]]:
        if theta.dim() != 2 or theta.shape[1] != self.num_params():
            raise DiffMatError(f"graph {self.name}: theta must be (B, {self.num_params()}), got {tuple(theta.shape)}")
        out: dict[str, dict[str, torch.Tensor]] = {}
        i = 0
        for n, p, k in self.param_slots():
            out.setdefault(n, {})[p] = theta[:, i:i + k]
            i += k
        return out

    # ---- evaluation --------------------------------------------------------------------------
    def _static(self, order: list[str], overrides: dict) -> set[str]:
        static = set()
        for n in order:
            node = self.nodes[n]
            if n in overrides or any(t.requires_grad for t in node.theta.values()):
                continue
            if all(src in static for src, _ in filter(None, self.links[n])):
                static.add(n)
        return static

    def forward(self, size: int = 512, seed: int = 0, theta: torch.Tensor | None = None,
                cache: bool = True) -> dict[str, torch.Tensor]:
        """Evaluate the graph at ``size`` pixels with graph seed ``seed``.

        ``theta`` (B, P) evaluates a batch of normalised parameter vectors. Returns the named
        outputs; their batch is B (or 1 when nothing varies in the batch).
        """
        if not self.outputs:
            raise DiffMatError(f"graph {self.name}: no outputs set")
        device = next((t.device for t in self.parameters()), torch.device("cpu"))
        dtype = next((t.dtype for t in self.parameters()), torch.float32)
        ctx = EvalContext(size=size, seed=seed, device=device, dtype=dtype)
        overrides = self._split(theta) if theta is not None else {}
        order = self.order()
        static = self._static(order, overrides) if cache else set()
        remaining = {n: 0 for n in order}
        frontier = {n for n, _ in self.outputs.values()}
        for n in order:
            for src, _ in filter(None, self.links[n]):
                remaining[src] += 1
                if n not in static:
                    frontier.add(src)
        for n, _ in self.outputs.values():
            remaining[n] += 1
        values: dict[str, tuple] = {}
        for n in order:
            node = self.nodes[n]
            key = (n, size, seed, str(device), dtype)
            if key in self._cache and n in static:
                result = self._cache[key]
            else:
                args = []
                for ref in self.links[n]:
                    if ref is None:
                        args.append(None)
                    else:
                        src, out = ref
                        args.append(values[src][self.nodes[src].spec.outputs.index(out)])
                result = node(*args, ctx=ctx, override=overrides.get(n))
                result = result if isinstance(result, tuple) else (result,)
                if n in static and n in frontier:
                    result = self._cache[key] = tuple(r.detach() for r in result)
            values[n] = result
            for src, _ in filter(None, self.links[n]):
                remaining[src] -= 1
                if remaining[src] == 0:
                    del values[src]
        return {u: values[n][self.nodes[n].spec.outputs.index(o)] for u, (n, o) in self.outputs.items()}

    def clear_cache(self):
        """Drop cached outputs (after changing frozen parameters by hand)."""
        self._cache.clear()

    def _apply(self, fn, *args, **kwargs):
        self._cache.clear()
        return super()._apply(fn, *args, **kwargs)
