"""Node: the parameter-holding module around a NodeSpec's functional op (like torch.nn around
torch.nn.functional), and ParameterSet, the normalised parameter storage it shares with
graph-level parameters.
"""
from __future__ import annotations

from dataclasses import dataclass

import torch
from torch import nn

from ..errors import DiffMatError
from ..functional.common import check_image, check_size
from .registry import get_spec
from .spec import NodeSpec, Param

CHANNELS = {"gray": (1,), "color": (4,), "any": (1, 4)}


@dataclass(frozen=True)
class EvalContext:
    """What every node of one evaluation shares: output size (pixels), graph seed, device, dtype."""

    size: int = 512
    seed: int = 0
    device: torch.device | str = "cpu"
    dtype: torch.dtype = torch.float32


def _check_discrete(spec: NodeSpec, p: Param, value):
    where = f"{spec.name}.{p.name}"
    if p.kind == "bool":
        if value in (0, 1, True, False):
            return bool(value)
        raise DiffMatError(f"{where}: expected a boolean, got {value!r}")
    if p.kind in ("int", "enum"):
        if isinstance(value, bool) or not isinstance(value, (int, float)) or int(value) != value:
            raise DiffMatError(f"{where}: expected an integer, got {value!r}")
        value = int(value)
        if p.kind == "enum" and value not in p.choices:
            raise DiffMatError(f"{where}: unknown value {value}; expected one of {list(p.choices)}")
        if p.kind == "int" and not p.min <= value <= p.max:
            raise DiffMatError(f"{where}: {value} is outside [{p.min:g}, {p.max:g}]")
        return value
    if not isinstance(value, str):
        raise DiffMatError(f"{where}: expected a string, got {value!r}")
    return value


class ParameterSet(nn.Module):
    """Continuous parameters stored normalised in [0, 1] between per-parameter ranges, plus fixed
    (discrete) values. ``values()`` maps the stored values to real ones, clamping first so that an
    optimiser can never push a parameter outside its domain (the MATch paper, section 5.1).

    Shared by ``Node`` and by graph-level parameter sets (a translated graph's exposed parameters);
    ``MaterialGraph`` builds its parameter vector from every set it holds.
    """

    def __init__(self, label: str):
        super().__init__()
        self.label = label
        self.theta = nn.ParameterDict()
        self.ranges: dict[str, tuple[float, float]] = {}
        self.fixed: dict[str, object] = {}

    def optimizable(self, name: str) -> bool:
        """Whether continuous parameter ``name`` may be optimised at all."""
        return True

    def _store(self, name: str, value, lo: float, hi: float, size: int | None, widen: bool, trainable: bool):
        where = f"{self.label}.{name}"
        try:
            t = torch.as_tensor(value, dtype=torch.float32).reshape(-1).clone()
        except (TypeError, ValueError):
            raise DiffMatError(f"{where}: expected a number or a list of numbers, got {value!r}") from None
        if size is not None and t.numel() == 1 and size > 1:
            t = t.expand(size).clone()
        if size is not None and t.numel() != size:
            raise DiffMatError(f"{where}: expected {size} component(s), got {t.numel()}")
        if not torch.isfinite(t).all():
            raise DiffMatError(f"{where}: value {value!r} is not finite")
        lo, hi = float(lo), float(hi)
        if t.numel() and (t.min() < lo or t.max() > hi):
            if not widen:
                raise DiffMatError(f"{where}: value {value!r} is outside [{lo:g}, {hi:g}]")
            lo, hi = min(lo, float(t.min())), max(hi, float(t.max()))
        self.ranges[name] = (lo, hi)
        norm = (t - lo) / (hi - lo) if hi > lo else torch.zeros_like(t)
        self.theta[name] = nn.Parameter(norm, requires_grad=trainable)

    def values(self, override: dict[str, torch.Tensor] | None = None) -> dict[str, torch.Tensor]:
        """Real values of the continuous parameters: (k,) tensors, or (B, k) where ``override``
        supplies a batch of normalised values for that parameter."""
        out = {}
        for name, t in self.theta.items():
            if override and name in override:
                t = override[name]
            lo, hi = self.ranges[name]
            out[name] = lo + torch.clamp(t, 0.0, 1.0) * (hi - lo)
        return out

    def set_values(self, **real_values):
        """Set continuous parameters from real (not normalised) values, within their ranges."""
        with torch.no_grad():
            for name, value in real_values.items():
                if name not in self.theta:
                    raise DiffMatError(f"{self.label}: no continuous parameter {name!r}")
                lo, hi = self.ranges[name]
                t = torch.as_tensor(value, dtype=self.theta[name].dtype).reshape(self.theta[name].shape)
                if (t < lo).any() or (t > hi).any():
                    raise DiffMatError(f"{self.label}.{name}: value {value!r} is outside [{lo:g}, {hi:g}]")
                self.theta[name].copy_((t - lo) / (hi - lo) if hi > lo else torch.zeros_like(t))


class Node(ParameterSet):
    """One node of a material graph.

    ``params`` overrides the spec's defaults by name. A continuous value outside the parameter's
    range is an error unless ``widen_ranges`` is set (the translator sets it for real files, whose
    values may lie outside a slider's range); then the range grows to hold it. ``seed`` is the
    node's random seed, added to the graph's.
    """

    def __init__(self, spec: NodeSpec | str, params: dict | None = None, *, seed: int = 0,
                 widen_ranges: bool = False):
        spec = get_spec(spec) if isinstance(spec, str) else spec
        super().__init__(spec.name)
        self.spec = spec
        params = dict(params or {})
        unknown = set(params) - set(spec.param_index)
        if unknown:
            raise DiffMatError(f"{spec.name}: unknown parameter(s) {sorted(unknown)}")
        self.seed = int(seed)
        for p in spec.params:
            value = params.get(p.name, p.default)
            if p.continuous:
                self._store(p.name, value, p.min, p.max, p.size, widen_ranges, p.optimizable)
            else:
                self.fixed[p.name] = _check_discrete(spec, p, value)

    def optimizable(self, name: str) -> bool:
        return self.spec.param(name).optimizable

    def forward(self, *images, ctx: EvalContext | None = None, override=None):
        ctx = ctx or EvalContext()
        spec = self.spec
        if len(images) > len(spec.inputs):
            raise DiffMatError(f"{spec.name}: takes {len(spec.inputs)} image input(s), got {len(images)}")
        padded = list(images) + [None] * (len(spec.inputs) - len(images))
        for slot, img in zip(spec.inputs, padded):
            if img is None:
                if not slot.optional:
                    raise DiffMatError(f"{spec.name}: input {slot.name!r} is not connected")
                continue
            check_image(img, f"{spec.name}.{slot.name}", CHANNELS[slot.channels])
            check_size(img.shape[-1], f"{spec.name}.{slot.name} width")
            check_size(img.shape[-2], f"{spec.name}.{slot.name} height")
        kwargs = dict(self.fixed)
        kwargs.update(self.values(override))
        context = {"size": check_size(ctx.size), "seed": ctx.seed + self.seed,
                   "device": ctx.device, "dtype": ctx.dtype}
        kwargs.update({k: context[k] for k in spec.context})
        return spec.fn(*padded, **kwargs)

    def extra_repr(self) -> str:
        return self.spec.name
