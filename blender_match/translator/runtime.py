"""SbsGraph: a MaterialGraph that also holds a translated graph's exposed parameters.

How exposed parameters live at runtime (the choice this module implements):

- Every exposed parameter of the root graph (a ``paraminput`` with a value type) is a graph-level
  parameter held by ``graph.exposed`` (an ``ExposedParameters`` module). Float ones are stored
  normalised in [0, 1] between a range (the widget's min/max, widened to hold the default) like
  node parameters, and are optimisable; int, bool and string ones are fixed values.
- A node parameter whose .sbs value is a function graph of exposed parameters is *bound*:
  ``graph.bind(node, param, function_graph)``. Before the node runs, a forward pre-hook evaluates
  the function graph with torch (``diffmat.functional.function_graph``) from the current exposed
  values and feeds the result to the node as its parameter value, so gradients flow from the node
  back to the exposed parameters. A bound continuous parameter is never optimisable itself.
- The optimisable vector (``get_vector``/``set_vector``/``forward(theta=...)``/``param_names``) is the
  node parameters MaterialGraph already handles followed by the exposed float parameters, named
  ``exposed.NAME``. ``set_mode`` picks what is free: ``"exposed"`` (exposed parameters only),
  ``"exposed_plus"`` (exposed parameters and every unbound node parameter), ``"all"`` (every node
  parameter; the translator then folds function graphs into constants and binds nothing).
"""
from __future__ import annotations

import fnmatch
import math

import torch
from torch import nn

from ..diffmat.errors import DiffMatError
from ..diffmat.functional import function_graph as fgraph
from ..diffmat.graph import MaterialGraph

MODES = ("exposed", "exposed_plus", "all")
EXPOSED = "exposed"  # the pseudo node name of exposed parameters in param_slots / param_names


def fit_components(values: list, size: int | None, default=None) -> list:
    """Make a list of numbers ``size`` long: a scalar spreads, extra components are dropped,
    missing ones come from ``default`` (or repeat the last)."""
    values = list(values)
    if size is None or len(values) == size:
        return values
    if len(values) == 1:
        return values * size
    if len(values) > size:
        return values[:size]
    fill = list(default) if isinstance(default, (list, tuple)) and len(default) == size else [values[-1]] * size
    return values + fill[len(values):]


class ExposedParameters(nn.Module):
    """The graph-level (exposed) parameters: float ones normalised in ``theta``, others fixed."""

    def __init__(self):
        super().__init__()
        self.theta = nn.ParameterDict()
        self.ranges: dict[str, tuple[float, float]] = {}
        self.fixed: dict[str, object] = {}
        self.kinds: dict[str, str] = {}

    def add(self, name: str, default, *, kind: str = "float", min: float = 0.0, max: float = 1.0):
        if name in self.kinds:
            raise DiffMatError(f"exposed parameter {name!r} declared twice")
        self.kinds[name] = kind
        if kind != "float":
            self.fixed[name] = default
            return
        t = torch.as_tensor(default, dtype=torch.float32).reshape(-1).clone()
        if not torch.isfinite(t).all():
            raise DiffMatError(f"exposed parameter {name!r}: default {default!r} is not finite")
        lo, hi = float(min), float(max)
        if t.numel():
            lo, hi = builtins_min(lo, float(t.min())), builtins_max(hi, float(t.max()))
        if not hi > lo:
            hi = lo + 1.0
        self.ranges[name] = (lo, hi)
        self.theta[name] = nn.Parameter((t - lo) / (hi - lo))

    def values(self, override: dict | None = None) -> dict:
        out = dict(self.fixed)
        for name, t in self.theta.items():
            if override and name in override:
                t = override[name]
            lo, hi = self.ranges[name]
            out[name] = lo + torch.clamp(t, 0.0, 1.0) * (hi - lo)
        return out

    def set_values(self, **real_values):
        with torch.no_grad():
            for name, value in real_values.items():
                if name in self.fixed:
                    self.fixed[name] = value
                    continue
                if name not in self.theta:
                    raise DiffMatError(f"no exposed parameter {name!r}")
                lo, hi = self.ranges[name]
                t = torch.as_tensor(value, dtype=self.theta[name].dtype).reshape(self.theta[name].shape)
                self.theta[name].copy_(((t - lo) / (hi - lo)).clamp(0.0, 1.0))


builtins_min, builtins_max = min, max


class SbsGraph(MaterialGraph):
    """A MaterialGraph with exposed (graph-level) parameters and bound node parameters."""

    def __init__(self, name: str = "graph"):
        super().__init__(name)
        self.exposed = ExposedParameters()
        self.bindings: dict[str, dict[str, dict]] = {}
        self.mode = "exposed_plus"
        self._batch: dict | None = None
        self._hooks: dict[str, object] = {}

    # ---- building -------------------------------------------------------------------------
    def add(self, name, node, inputs=None, *, seed=0, **params):
        if name == EXPOSED:
            raise DiffMatError(f"graph {self.name}: node name {EXPOSED!r} is reserved")
        return super().add(name, node, inputs, seed=seed, **params)

    def expose(self, name: str, default, *, kind: str = "float", min: float = 0.0, max: float = 1.0):
        """Declare an exposed parameter (``kind`` float, int, bool or string)."""
        self.exposed.add(name, default, kind=kind, min=min, max=max)
        self._cache.clear()

    def bind(self, node: str, param: str, function_graph: dict):
        """Drive ``node.param`` by ``function_graph`` of the exposed parameters."""
        if node not in self.nodes:
            raise DiffMatError(f"graph {self.name}: bind to missing node {node!r}")
        module = self.nodes[node]
        if param not in module.spec.param_index:
            raise DiffMatError(f"graph {self.name}: node {node!r} has no parameter {param!r}")
        fgraph.validate(function_graph)
        unknown = fgraph.variables_of(function_graph) - set(self.exposed.kinds)
        if unknown:
            raise DiffMatError(f"graph {self.name}: {node}.{param} reads unknown variable(s) {sorted(unknown)}")
        self.bindings.setdefault(node, {})[param] = function_graph
        if param in module.theta:
            module.theta[param].requires_grad_(False)
        if node not in self._hooks:
            self._hooks[node] = module.register_forward_pre_hook(
                lambda mod, args, kwargs, _n=node: self._pre_hook(_n, mod, args, kwargs), with_kwargs=True)
        self._cache.clear()

    def set_mode(self, mode: str):
        """Choose the free parameters: "exposed", "exposed_plus" or "all" (see the module doc)."""
        if mode not in MODES:
            raise DiffMatError(f"graph {self.name}: unknown mode {mode!r}; expected one of {list(MODES)}")
        self.mode = mode
        for n, node in self.nodes.items():
            for p, t in node.theta.items():
                free = (mode != "exposed" and node.spec.param(p).optimizable
                        and p not in self.bindings.get(n, {}))
                t.requires_grad_(free)
        for t in self.exposed.theta.values():
            t.requires_grad_(True)
        self._cache.clear()

    # ---- bound parameters ------------------------------------------------------------------
    def _pre_hook(self, name, module, args, kwargs):
        batch = self._batch
        variables = self.exposed.values(batch)
        override = dict(kwargs.get("override") or {})
        device = next((t.device for t in module.theta.values()), torch.device("cpu"))
        dtype = next((t.dtype for t in module.theta.values()), torch.float32)
        for param, graph in self.bindings[name].items():
            p = module.spec.param(param)
            value = fgraph.evaluate(graph, variables, device=device, dtype=dtype)
            if param in module.theta:
                if isinstance(value, str):
                    raise DiffMatError(f"{name}.{param}: the bound function returns a string")
                k = module.theta[param].numel()
                value = _fit_tensor(value, k, f"{name}.{param}")
                lo, hi = module.ranges[param]
                override[param] = (value - lo) / (hi - lo) if hi > lo else torch.zeros_like(value)
            else:
                module.fixed[param] = _discrete(p, value, f"{name}.{param}")
        kwargs["override"] = override
        return args, kwargs

    def _exposed_live(self) -> bool:
        return self._batch is not None or any(t.requires_grad for t in self.exposed.theta.values())

    def _static(self, order, overrides):
        if self.bindings and self._exposed_live():
            overrides = {**overrides, **{n: {} for n in self.bindings}}
        return super()._static(order, overrides)

    # ---- the parameter vector ----------------------------------------------------------------
    def _tensor(self, n: str, p: str) -> torch.Tensor:
        return self.exposed.theta[p] if n == EXPOSED else self.nodes[n].theta[p]

    def param_slots(self):
        slots = super().param_slots()
        return slots + [(EXPOSED, p, t.numel()) for p, t in self.exposed.theta.items() if t.requires_grad]

    def get_vector(self) -> torch.Tensor:
        slots = self.param_slots()
        if not slots:
            return torch.zeros(0)
        return torch.cat([self._tensor(n, p).detach().reshape(-1) for n, p, _ in slots])

    def set_vector(self, vector: torch.Tensor):
        if vector.numel() != self.num_params():
            raise DiffMatError(f"graph {self.name}: parameter vector has {vector.numel()} values, "
                               f"expected {self.num_params()}")
        with torch.no_grad():
            i = 0
            for n, p, k in self.param_slots():
                t = self._tensor(n, p)
                t.copy_(vector[i:i + k].reshape(t.shape).to(t))
                i += k
        self._cache.clear()

    def _split(self, theta):
        out = super()._split(theta)
        self._batch = out.pop(EXPOSED, None)
        return out

    def forward(self, size: int = 512, seed: int = 0, theta=None, cache: bool = True):
        self._batch = None
        try:
            return super().forward(size, seed, theta, cache)
        finally:
            self._batch = None

    def _select(self, pattern: str, trainable: bool):
        hits = 0
        for p, t in self.exposed.theta.items():
            if fnmatch.fnmatchcase(f"{EXPOSED}.{p}", pattern) or fnmatch.fnmatchcase(EXPOSED, pattern):
                t.requires_grad_(trainable)
                hits += 1
        for n, node in self.nodes.items():
            for p, t in node.theta.items():
                if fnmatch.fnmatchcase(f"{n}.{p}", pattern) or fnmatch.fnmatchcase(n, pattern):
                    bound = p in self.bindings.get(n, {})
                    t.requires_grad_(trainable and node.spec.param(p).optimizable and not bound)
                    hits += 1
        if not hits:
            raise DiffMatError(f"graph {self.name}: no parameter matches {pattern!r}")
        self._cache.clear()


def _fit_tensor(value: torch.Tensor, k: int, where: str) -> torch.Tensor:
    n = value.shape[-1]
    if n == k:
        return value
    if n == 1:
        return value.expand(*value.shape[:-1], k)
    if n > k:
        return value[..., :k]
    raise DiffMatError(f"{where}: the bound function gives {n} component(s), the parameter has {k}")


def _discrete(p, value, where: str):
    if p.kind == "string":
        if not isinstance(value, str):
            raise DiffMatError(f"{where}: expected a string")
        return value
    if isinstance(value, str):
        raise DiffMatError(f"{where}: expected a number, got a string")
    x = float(value.reshape(-1)[0])
    if not math.isfinite(x):
        raise DiffMatError(f"{where}: value {x} is not finite")
    if p.kind == "bool":
        return x > 0.5
    x = int(round(x))
    if p.kind == "enum" and x not in p.choices:
        raise DiffMatError(f"{where}: unknown value {x}; expected one of {list(p.choices)}")
    if p.kind == "int" and not p.min <= x <= p.max:
        raise DiffMatError(f"{where}: {x} is outside [{p.min:g}, {p.max:g}]")
    return x
