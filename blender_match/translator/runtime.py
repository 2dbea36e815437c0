"""SbsGraph: a MaterialGraph that also holds a translated graph's exposed parameters.

How exposed parameters live at runtime (the choice this module implements):

- Every exposed parameter of the root graph (a ``paraminput`` with a value type) is a graph-level
  parameter held by ``graph.exposed`` (an ``ExposedParameters`` module). Float ones are stored
  normalised in [0, 1] between a range (the widget's min/max, widened to hold the default) like
  node parameters, and are optimisable; int, bool and string ones are fixed values.
- A node parameter whose .sbs value is a function graph of exposed parameters is *bound*:
  ``graph.bind(node, param, function_graph)``, which compiles the function graph once. Before the
  node runs, a forward pre-hook evaluates it with torch (``diffmat.functional.function_graph``)
  from the current exposed values and feeds the result to the node as its parameter value, so
  gradients flow from the node back to the exposed parameters. A bound continuous parameter is never optimisable itself.
- The optimisable vector (``get_vector``/``set_vector``/``forward(theta=...)``/``param_names``) is the
  node parameters MaterialGraph already handles followed by the exposed float parameters, named
  ``exposed.NAME``. ``set_mode`` picks what is free: ``"exposed"`` (exposed parameters only),
  ``"exposed_plus"`` (exposed parameters and every unbound node parameter), ``"all"`` (every node
  parameter; the translator then folds function graphs into constants and binds nothing).
"""
from __future__ import annotations

import math

import torch

from ..diffmat.errors import DiffMatError
from ..diffmat.functional import function_graph as fgraph
from ..diffmat.graph import MaterialGraph
from ..diffmat.nodes.module import ParameterSet

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


class ExposedParameters(ParameterSet):
    """The graph-level (exposed) parameters: float ones normalised in ``theta`` (ranged by the
    widget's min/max, widened to hold the default), others fixed values by name."""

    def __init__(self) -> None:
        super().__init__(EXPOSED)
        self.kinds: dict[str, str] = {}

    def add(self, name: str, default, *, kind: str = "float", min: float = 0.0, max: float = 1.0):
        if name in self.kinds:
            raise DiffMatError(f"exposed parameter {name!r} declared twice")
        self.kinds[name] = kind
        if kind != "float":
            self.fixed[name] = default
            return
        if not max > min:
            max = min + 1.0
        self._store(name, default, min, max, None, widen=True, trainable=True)

    def values(self, override: dict | None = None) -> dict:
        return {**self.fixed, **super().values(override)}

    def set_values(self, **real_values):
        fixed = {k: v for k, v in real_values.items() if k in self.fixed}
        self.fixed.update(fixed)
        super().set_values(**{k: v for k, v in real_values.items() if k not in fixed})


class SbsGraph(MaterialGraph):
    """A MaterialGraph with exposed (graph-level) parameters and bound node parameters."""

    report: dict  # the translation report, set by ``translator.translate``

    def __init__(self, name: str = "graph"):
        super().__init__(name)
        self.exposed = ExposedParameters()
        self.bindings: dict[str, dict[str, dict]] = {}
        self._compiled: dict[str, dict[str, fgraph.CompiledGraph]] = {}  # bindings, compiled once
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
        self._changed()

    def bind(self, node: str, param: str, function_graph: dict):
        """Drive ``node.param`` by ``function_graph`` of the exposed parameters."""
        if node not in self.nodes:
            raise DiffMatError(f"graph {self.name}: bind to missing node {node!r}")
        module = self.node(node)
        if param not in module.spec.param_index:
            raise DiffMatError(f"graph {self.name}: node {node!r} has no parameter {param!r}")
        compiled = fgraph.compile_graph(function_graph)
        unknown = compiled.variables - set(self.exposed.kinds)
        if unknown:
            raise DiffMatError(f"graph {self.name}: {node}.{param} reads unknown variable(s) {sorted(unknown)}")
        self.bindings.setdefault(node, {})[param] = function_graph
        self._compiled.setdefault(node, {})[param] = compiled
        if param in module.theta:
            module.theta[param].requires_grad_(False)
        if node not in self._hooks:
            self._hooks[node] = module.register_forward_pre_hook(
                lambda mod, args, kwargs, _n=node: self._pre_hook(_n, mod, args, kwargs), with_kwargs=True)
        self._changed()

    def set_mode(self, mode: str):
        """Choose the free parameters: "exposed", "exposed_plus" or "all" (see the module doc)."""
        if mode not in MODES:
            raise DiffMatError(f"graph {self.name}: unknown mode {mode!r}; expected one of {list(MODES)}")
        self.mode = mode
        for n, ps in self.parameter_sets().items():
            for p, t in ps.theta.items():
                t.requires_grad_(self.may_train(n, p) and (n == EXPOSED or mode != "exposed"))
        self._changed()

    # ---- bound parameters ------------------------------------------------------------------
    def _pre_hook(self, name, module, args, kwargs):
        batch = self._batch
        variables = self.exposed.values(batch)
        override = dict(kwargs.get("override") or {})
        device = next((t.device for t in module.theta.values()), torch.device("cpu"))
        dtype = next((t.dtype for t in module.theta.values()), torch.float32)
        for param, evaluate in self._compiled[name].items():
            p = module.spec.param(param)
            value = evaluate(variables, device=device, dtype=dtype)
            if param in module.theta:
                if isinstance(value, str):
                    raise DiffMatError(f"{name}.{param}: the bound function returns a string")
                k = module.theta[param].numel()
                value = fgraph.fit_components(value, k, f"{name}.{param}", fill=p.default)
                lo, hi = module.ranges[param]
                override[param] = (value - lo) / (hi - lo) if hi > lo else torch.zeros_like(value)
            else:
                module.fixed[param] = _discrete(p, value, f"{name}.{param}")
        kwargs["override"] = override
        return args, kwargs

    def _dynamic(self) -> set[str]:
        """Also the nodes bound to trainable exposed parameters (a constant binding, or one of
        frozen parameters, leaves its node cacheable)."""
        dynamic = super()._dynamic()
        if any(t.requires_grad for t in self.exposed.theta.values()):
            dynamic.update(n for n, b in self._compiled.items() if any(c.variables for c in b.values()))
        return dynamic

    # ---- the parameter vector ----------------------------------------------------------------
    def parameter_sets(self):
        return {**super().parameter_sets(), EXPOSED: self.exposed}

    def may_train(self, owner: str, param: str) -> bool:
        return super().may_train(owner, param) and param not in self.bindings.get(owner, {})

    def _split(self, theta, plan):
        out = super()._split(theta, plan)
        self._batch = out.pop(EXPOSED, None)
        return out

    def forward(self, size: int = 512, seed: int = 0, theta=None, cache: bool = True):
        if theta is not None and theta.dim() == 2 and theta.shape[0] > 1 and self._discrete_varies(theta):
            return _stack_outputs([self.forward(size, seed, row[None], cache) for row in theta])
        self._batch = None
        try:
            return super().forward(size, seed, theta, cache)
        finally:
            self._batch = None

    def _discrete_varies(self, theta: torch.Tensor) -> bool:
        """Whether a discrete parameter (an integer, a switch) bound to the exposed parameters
        takes different values across the batch ``theta`` (B, P): a node draws one value for its
        whole batch, so such a batch is evaluated item by item."""
        discrete = [(n, p, c) for n, b in self._compiled.items() for p, c in b.items()
                    if c.variables and p not in self.node(n).theta]
        if not discrete:
            return False
        batch = MaterialGraph._split(self, theta, self.plan()).get(EXPOSED)
        if batch is None:
            return False
        variables = self.exposed.values(batch)
        for name, param, compiled in discrete:
            value = compiled(variables)
            if isinstance(value, str):
                continue
            value = torch.as_tensor(value).detach()
            if value.dim() == 0 or value.shape[0] != theta.shape[0]:
                continue  # not per item: the same for the whole batch
            spec, where = self.node(name).spec.param(param), f"{name}.{param}"
            first = _discrete(spec, value[0], where)
            if any(_discrete(spec, row, where) != first for row in value[1:]):
                return True
        return False


def _stack_outputs(items: list[dict[str, torch.Tensor]]) -> dict[str, torch.Tensor]:
    """The outputs of single evaluations as one batch (an output that is the same for every item
    comes back with batch 1 from each and is stacked all the same)."""
    return {usage: torch.cat([item[usage] for item in items]) for usage in items[0]}


def _discrete(p, value, where: str):
    if p.kind == "string":
        if not isinstance(value, str):
            raise DiffMatError(f"{where}: expected a string")
        return value
    if isinstance(value, str):
        raise DiffMatError(f"{where}: expected a number, got a string")
    x = float(torch.as_tensor(value).detach().reshape(-1)[0])
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
