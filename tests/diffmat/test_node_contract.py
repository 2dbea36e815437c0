"""The contract every registered node keeps (issue 2): shapes and range, tiling, determinism,
both colour modes, batched parameters, a float64 finite-difference gradient check on every
continuous parameter, the same output with autograd on and under ``torch.no_grad``, resolution
independence for generators, and clear errors on bad input.

Per-node known-value tests against the documented formulas live in the family test files.
"""
from __future__ import annotations

import pytest
import torch
from imagecheck import assert_tiles, box_down, smooth_tiling_image

from blender_match.diffmat import DiffMatError, EvalContext, Node, all_specs

SPECS = all_specs()
IDS = [s.name for s in SPECS]
SIZE = 32


def _inputs(spec, channels_any: int, size: int = SIZE, dtype=torch.float32):
    images = []
    for i, slot in enumerate(spec.inputs):
        if slot.optional:
            images.append(None)
            continue
        ch = {"gray": 1, "color": 4}.get(slot.channels, channels_any)
        images.append(smooth_tiling_image(ch, size, seed=11 + i, dtype=dtype))
    return images


def _modes(spec):
    return (1, 4) if any(s.channels == "any" and not s.optional for s in spec.inputs) else (4,)


def _outputs(result):
    return result if isinstance(result, tuple) else (result,)


@pytest.mark.parametrize("spec", SPECS, ids=IDS)
def test_shapes_range_tiling_determinism(spec):
    for mode in _modes(spec):
        node = Node(spec)
        ctx = EvalContext(size=SIZE, seed=3)
        first = _outputs(node(*_inputs(spec, mode), ctx=ctx))
        again = _outputs(node(*_inputs(spec, mode), ctx=ctx))
        assert len(first) == len(spec.outputs)
        for out, out2 in zip(first, again):
            assert out.dim() == 4 and out.shape[-2:] == (SIZE, SIZE), out.shape
            assert out.shape[1] in (1, 4)
            assert torch.isfinite(out).all()
            assert out.min() >= -1e-4 and out.max() <= 1 + 1e-4, (out.min().item(), out.max().item())
            assert torch.equal(out, out2), "same seed and parameters must give the same output"
            assert_tiles(out.detach())


@pytest.mark.parametrize("spec", SPECS, ids=IDS)
def test_batched_parameters(spec):
    node = Node(spec)
    if not node.theta:
        pytest.skip("no continuous parameter")
    ctx = EvalContext(size=16, seed=1)
    images = _inputs(spec, _modes(spec)[-1], size=16)
    g = torch.Generator().manual_seed(5)
    override = {n: torch.rand(2, t.numel(), generator=g) * 0.6 + 0.2 for n, t in node.theta.items()}
    batched = _outputs(node(*images, ctx=ctx, override=override))
    for b in range(2):
        single = _outputs(node(*images, ctx=ctx, override={n: v[b:b + 1] for n, v in override.items()}))
        for out, one in zip(batched, single):
            assert out.shape[0] == 2
            torch.testing.assert_close(out[b:b + 1], one, atol=1e-5, rtol=1e-4)


@pytest.mark.parametrize("spec", SPECS, ids=IDS)
def test_gradients_match_finite_differences(spec):
    base = Node(spec).double()
    names = [n for n, t in base.theta.items() if t.requires_grad]
    if not names:
        pytest.skip("no optimisable parameter")
    ctx = EvalContext(size=16, seed=2, dtype=torch.float64)
    images = _inputs(spec, _modes(spec)[-1], size=16, dtype=torch.float64)
    g = torch.Generator().manual_seed(7)
    for name in names:
        point = (torch.rand(base.theta[name].numel(), generator=g, dtype=torch.float64) * 0.6 + 0.2)[None]

        def fn(t, name=name):
            outs = _outputs(base(*images, ctx=ctx, override={name: t}))
            return torch.cat([o.reshape(-1) for o in outs])

        assert torch.autograd.gradcheck(fn, (point.requires_grad_(),), eps=1e-6, atol=1e-4, rtol=1e-3,
                                        fast_mode=True), f"{spec.name}.{name}"


@pytest.mark.parametrize("spec", SPECS, ids=IDS)
def test_grad_and_no_grad_agree(spec):
    """Ops with a separate no-grad path (an in-place twin) compute what their autograd path does."""
    for mode in _modes(spec):
        node = Node(spec)
        for t in node.theta.values():
            t.requires_grad_(True)
        ctx = EvalContext(size=SIZE, seed=5)
        images = _inputs(spec, mode)
        with torch.no_grad():
            plain = _outputs(node(*images, ctx=ctx))
        tracked = _outputs(node(*[None if i is None else i.clone().requires_grad_() for i in images], ctx=ctx))
        for a, b in zip(plain, tracked):
            torch.testing.assert_close(a, b.detach(), atol=1e-6, rtol=1e-5)


GENERATORS = [s for s in SPECS if s.kind == "generator"]


@pytest.mark.parametrize("spec", GENERATORS, ids=[s.name for s in GENERATORS])
def test_generator_resolution_independence(spec):
    node = Node(spec)
    with torch.no_grad():
        big = _outputs(node(ctx=EvalContext(size=1024, seed=4)))
        small = _outputs(node(ctx=EvalContext(size=512, seed=4)))
    for b, s in zip(big, small):
        diff = (box_down(b) - s).abs().mean().item()
        assert diff < 0.03, f"1024 render box-downsampled differs from the 512 render by {diff:.4f}"


@pytest.mark.parametrize("spec", SPECS, ids=IDS)
def test_bad_input_is_a_clear_error(spec):
    node = Node(spec)
    with pytest.raises(DiffMatError):
        node(*_inputs(spec, 4), ctx=EvalContext(size=48))
    required = [i for i, s in enumerate(spec.inputs) if not s.optional]
    if required:
        images = _inputs(spec, 4)
        images[required[0]] = torch.rand(1, 3, SIZE, SIZE)
        with pytest.raises(DiffMatError):
            node(*images, ctx=EvalContext(size=SIZE))
        images[required[0]] = torch.rand(SIZE, SIZE)
        with pytest.raises(DiffMatError):
            node(*images, ctx=EvalContext(size=SIZE))


def test_seam_check_catches_an_image_that_does_not_tile():
    ramp = torch.linspace(0, 1, SIZE).expand(1, 1, SIZE, SIZE)
    with pytest.raises(AssertionError, match="seam jump"):
        assert_tiles(ramp)
    assert_tiles(torch.roll(smooth_tiling_image(1, SIZE), 5, dims=-1))
