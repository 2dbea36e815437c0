"""Per-graph parameter prediction (the MATch paper, section 4.2), trained on synthetic data.

The design is the paper's: a frozen VGG19 descriptor of the photo feeds a small per-graph
multi-layer perceptron whose sigmoid output is the graph's normalised trainable parameter vector
(P,). Two departures, both for size and CPU time:

- the descriptor is the compact one of ``selection.descriptor`` (2944 values instead of the
  610k of the flattened Gram matrices), standardised and folded by a fixed count sketch (each
  input added, with a fixed sign, into one of ``SKETCH_DIM`` sums chosen by an integer hash of
  its index: no random generator, no stored matrix), then an MLP 384 -> 128 -> 128 -> P instead
  of l -> 3P -> 3P -> P; weights are stored in float16, about 0.17 MB a graph. With a few hundred
  training examples a network learns mostly the mean and the few directions the image explains:
  on the same examples the 2944 -> 256 -> 256 network of earlier versions (1.7 MB) reached the
  same validation error (docs/benchmarks.md);
- parameters the library never varies (those without a ``sample_ranges`` entry) are not learnt:
  the output keeps the graph's default there (``mask``), since no training example could teach
  anything else.

Training (``train_graph``) follows the paper: synthetic examples from the graph itself, a
parameter L1 loss first (``fit_params``), then a short phase adding the rendering (style) loss of eq. 4 with
lambda_g = 0.05. Rendering is the cost on a CPU (a few tenths of a second to seconds per
example), so the examples are rendered once and reused for every epoch rather than drawn anew each
iteration: samples 0..BANK_SIZE-1 are the bank's (graph seed 0: one pass builds both), the rest
are ``sample_params(name, k)`` for k >= BANK_SIZE with a random graph seed, a quarter of them
jittered by up to 0.1 around the sample in normalised space ("uniform in [0, 1] around the
samples"). The last eighth of those is held out for validation, which also picks the epoch kept
(early stopping: with so few examples the network overfits within tens of epochs); the reported
error is the mean absolute error in normalised space over the sampled components (the selection
benchmark measures it on targets nothing was selected on).

Training is resumable: ``<name>.train.pt`` in the models folder checkpoints the examples rendered
so far (``resume=True`` continues from them); it is deleted when the graph is done (unless
``keep_data``: then ``resume=True`` re-trains the network on the same examples in seconds).
Outputs: ``<name>.predictor.pt`` (a state_dict, ``torch.load(weights_only=True)``) and
``<name>.predictor.json`` (metadata: sizes, the training figures and ``graph_hash``, the SHA-256
of the graph's .sbs and .json, which tells when the model is stale).
"""
from __future__ import annotations

import json
import math
import random
import time

import torch
from torch import nn

from ..diffmat.descriptor import TextureDescriptor, style_loss
from ..diffmat.render import render_maps
from ..errors import Cancelled, OptionError
from ..library import library_entry
from ..safe_files import write_json_atomic
from .bank import (
    BANK_SEED,
    BANK_SIZE,
    SampleSpace,
    bank_is_current,
    describe,
    graph_hash,
    load_torch,
    models_dir,
    render_images,
    save_torch,
    supersample,
    write_bank,
)
from .descriptor import DESCRIPTOR_DIM, DESCRIPTOR_KIND, DESCRIPTOR_SIZE, shared_vgg

SKETCH_DIM = 384
HIDDEN = 128
LAYERS = 2
PREDICTOR_FORMAT = 2  # raised when the network's layout changes: older files are stale
DEFAULT_SAMPLES = 256
DEFAULT_EPOCHS = 60
DEFAULT_RENDER_STEPS = 6
RENDER_SIZE = 64          # the rendering-loss phase renders and describes at this size
LAMBDA_G = 0.05           # the paper's weight of the style loss in eq. 4
JITTER_SHARE, JITTER = 0.25, 0.1
LR, WEIGHT_DECAY, DROPOUT, INPUT_NOISE = 3e-4, 1e-3, 0.3, 0.3
TRAIN_SEEDS = (1, 100_000)  # graph seeds of the training examples (benchmarks use others)
PREDICTOR_SUFFIX, META_SUFFIX, CHECKPOINT_SUFFIX = ".predictor.pt", ".predictor.json", ".train.pt"


def count_sketch(in_dim: int, out_dim: int) -> tuple[torch.Tensor, torch.Tensor]:
    """(bucket, sign) of every input index: a multiplicative hash (Knuth's constant) picks the
    bucket from its low bits and the sign from bit 16, the same on every machine and version."""
    h = (torch.arange(in_dim, dtype=torch.int64) * 2654435761 + 97) % (2 ** 32)
    return h % out_dim, ((h >> 16) & 1).float() * 2 - 1


class ParamPredictor(nn.Module):
    """Compact descriptor (B, D) -> normalised parameters (B, P) in [0, 1]: standardised input,
    folded to ``sketch`` values (``count_sketch``), ``layers`` hidden ReLU layers of ``hidden``
    units, a sigmoid; components outside ``mask`` return ``default``."""

    in_mean: torch.Tensor  # buffers (register_buffer), declared for the type checker
    in_std: torch.Tensor
    default: torch.Tensor
    mask: torch.Tensor
    bucket: torch.Tensor
    sign: torch.Tensor

    def __init__(self, in_dim: int, num_params: int, hidden: int = HIDDEN, layers: int = LAYERS,
                 sketch: int = SKETCH_DIM):
        super().__init__()
        blocks, width = [], sketch
        for _ in range(layers):
            blocks += [nn.Linear(width, hidden), nn.ReLU(), nn.Dropout(DROPOUT)]
            width = hidden
        blocks.append(nn.Linear(width, num_params))
        self.net = nn.Sequential(*blocks)
        self.register_buffer("in_mean", torch.zeros(in_dim))
        self.register_buffer("in_std", torch.ones(in_dim))
        self.register_buffer("default", torch.full((num_params,), 0.5))
        self.register_buffer("mask", torch.ones(num_params, dtype=torch.bool))
        bucket, sign = count_sketch(in_dim, sketch)
        self.register_buffer("bucket", bucket, persistent=False)
        self.register_buffer("sign", sign / (in_dim / sketch) ** 0.5, persistent=False)
        self.sketch = sketch

    def forward(self, descriptor: torch.Tensor) -> torch.Tensor:
        x = (descriptor.to(self.in_mean) - self.in_mean) / self.in_std
        folded = x.new_zeros(x.shape[0], self.sketch).index_add_(1, self.bucket, x * self.sign)
        return torch.where(self.mask, torch.sigmoid(self.net(folded)), self.default)


def predictor_paths(name: str, directory=None):
    base = models_dir(directory, name)
    return base / f"{name}{PREDICTOR_SUFFIX}", base / f"{name}{META_SUFFIX}", base / f"{name}{CHECKPOINT_SUFFIX}"


def read_meta(name: str, directory=None) -> dict | None:
    _, meta_path, _ = predictor_paths(name, directory)
    if not meta_path.is_file():
        return None
    return json.loads(meta_path.read_text(encoding="utf-8"))


def predictor_is_current(name: str, directory=None) -> bool:
    weights, _, _ = predictor_paths(name, directory)
    meta = read_meta(name, directory)
    return (meta is not None and weights.is_file() and meta.get("graph_sha256") == graph_hash(name)
            and meta.get("descriptor") == DESCRIPTOR_KIND and meta.get("format") == PREDICTOR_FORMAT)


def load_predictor(name: str, directory=None) -> ParamPredictor | None:
    """A graph's trained predictor in float32, eval mode (None when it has none)."""
    weights, _, _ = predictor_paths(name, directory)
    meta = read_meta(name, directory)
    state = load_torch(weights)
    if meta is None or state is None:
        return None
    model = ParamPredictor(meta["descriptor_dim"], meta["params"], meta["hidden"], meta["layers"], meta["sketch"])
    model.load_state_dict({k: (v.float() if v.is_floating_point() else v) for k, v in state.items()})
    return model.eval()


def save_predictor(model: ParamPredictor, name: str, meta: dict, directory=None, dtype=torch.float16):
    weights, meta_path, _ = predictor_paths(name, directory)
    state = {k: (v.detach().to(dtype) if v.is_floating_point() else v.detach()).cpu().clone()
             for k, v in model.state_dict().items()}
    save_torch(state, weights)
    write_json_atomic(meta_path, meta, overwrite=True)


def masked_l1(pred: torch.Tensor, truth: torch.Tensor, mask: torch.Tensor) -> torch.Tensor:
    """Mean absolute error over the sampled components (mask), averaged over the batch."""
    m = mask.to(pred.dtype)
    return ((pred - truth).abs() * m).sum() / (m.sum() * pred.shape[0]).clamp_min(1)


def _plan(name: str, samples: int, bank_size: int) -> list[tuple[int, int, bool]]:
    """(k, graph seed, jittered) of every training example; the first ``bank_size`` are the bank."""
    plan = []
    for k in range(samples):
        if k < bank_size:
            plan.append((k, BANK_SEED, False))
        else:
            rng = random.Random(f"{name}/train/{k}")
            plan.append((k, rng.randrange(*TRAIN_SEEDS), rng.random() < JITTER_SHARE))
    return plan


def _theta(space: SampleSpace, name: str, k: int, jitter: bool) -> torch.Tensor:
    if not jitter:
        return space.vector(k)
    return space.jittered(k, random.Random(f"{name}/jitter/{k}"), JITTER)


def _generate(space, plan, data, checkpoint, device, progress, cancel, batch=8):
    """Render and describe the examples of ``plan`` not yet in ``data`` (checkpointed per batch)."""
    graph = space.graph
    factor = supersample(library_entry(space.name))
    done = len(data["seeds"])
    while done < len(plan):
        if cancel is not None and cancel():
            raise Cancelled()
        t0 = time.perf_counter()
        group = plan[done:done + batch]
        thetas = torch.stack([_theta(space, space.name, k, jit) for k, _, jit in group])
        images, start = [], 0
        while start < len(group):  # one render per run of examples sharing a graph seed
            seed = group[start][1]
            end = next((i for i in range(start, len(group)) if group[i][1] != seed), len(group))
            images.append(render_images(graph, thetas[start:end].to(device), seed, DESCRIPTOR_SIZE, factor))
            start = end
        images = torch.cat(images)
        data["thetas"] = torch.cat([data["thetas"], thetas])
        data["descriptors"] = torch.cat([data["descriptors"], describe(images, device)])
        small = torch.nn.functional.interpolate(images, size=(RENDER_SIZE,) * 2, mode="bilinear",
                                                antialias=True, align_corners=False)
        data["images"] = torch.cat([data["images"], small.half().cpu()])
        data["seeds"] = torch.cat([data["seeds"], torch.tensor([p[1] for p in group], dtype=torch.int64)])
        done += len(group)
        graph.clear_cache()
        data["seconds"] = float(data["seconds"]) + time.perf_counter() - t0
        save_torch(data, checkpoint)
        if progress is not None:
            progress({"phase": "data", "done": done, "total": len(plan)})
    return data


def fit_params(model, x, y, xv, yv, mask, epochs, progress, cancel, seed):
    """Phase 1: parameter L1 loss only; returns the best-by-validation state and its error.
    The network starts at the training mean (last layer's bias its logit, weights shrunk): with
    a few hundred examples for ~100 parameters, most of which barely show in an image, the mean
    is a strong baseline, and what is learnt is the deviation from it that the image explains."""
    last = model.net[-1]
    with torch.no_grad():
        mean = y.mean(0).clamp(0.02, 0.98)
        last.bias.copy_(torch.log(mean / (1 - mean)))
        last.weight.mul_(0.1)
    gen = torch.Generator().manual_seed(seed)
    optimizer = torch.optim.AdamW(model.parameters(), lr=LR, weight_decay=WEIGHT_DECAY)
    decay = torch.optim.lr_scheduler.ExponentialLR(optimizer, 0.99)
    best_err, best_state = math.inf, None
    for epoch in range(epochs):
        if cancel is not None and cancel():
            raise Cancelled()
        model.train()
        order = torch.randperm(x.shape[0], generator=gen)
        for start in range(0, x.shape[0], 32):
            idx = order[start:start + 32]
            noisy = x[idx] + INPUT_NOISE * model.in_std * torch.randn(x[idx].shape, generator=gen)
            loss = masked_l1(model(noisy), y[idx], mask)
            optimizer.zero_grad(set_to_none=True)
            loss.backward()
            optimizer.step()
        decay.step()
        err = _val_error(model, xv, yv, mask)
        if err < best_err:
            best_err, best_state = err, {k: v.clone() for k, v in model.state_dict().items()}
        if progress is not None and (epoch % 10 == 9 or epoch == epochs - 1):
            progress({"phase": "fit", "done": epoch + 1, "total": epochs, "val_error": err})
    model.load_state_dict(best_state)
    return best_err


def _val_error(model, xv, yv, mask) -> float:
    model.eval()
    with torch.no_grad():
        return float(masked_l1(model(xv), yv, mask))


def _render_phase(model, graph, data, train_idx, mask, steps, device, progress, cancel, seed, batch=2):
    """Phase 2 (eq. 4): parameter L1 + LAMBDA_G x style loss of the predicted parameters'
    render against the example's, both at RENDER_SIZE px (Gram descriptor, as the fit's loss)."""
    gram = TextureDescriptor(scales=(RENDER_SIZE,), vgg=shared_vgg(device))
    gen = torch.Generator().manual_seed(seed + 1)
    optimizer = torch.optim.Adam(model.net.parameters(), lr=1e-4)
    model.to(device)
    for step in range(steps):
        if cancel is not None and cancel():
            raise Cancelled()
        model.train()
        optimizer.zero_grad(set_to_none=True)
        picks = train_idx[torch.randint(len(train_idx), (batch,), generator=gen)]
        for i in picks.tolist():
            pred = model(data["descriptors"][i:i + 1].to(device))
            image = render_maps(graph(size=RENDER_SIZE, seed=int(data["seeds"][i]), theta=pred))
            with torch.no_grad():
                target = gram(data["images"][i:i + 1].float().to(device))
            loss = masked_l1(pred, data["thetas"][i:i + 1].to(device), mask.to(device)) \
                + LAMBDA_G * style_loss(gram(image.clamp(0, 1)), target)[0]
            (loss / batch).backward()
        optimizer.step()
        graph.clear_cache()
        if progress is not None:
            progress({"phase": "render", "done": step + 1, "total": steps})
    model.cpu()


def train_graph(name: str, samples: int = DEFAULT_SAMPLES, epochs: int = DEFAULT_EPOCHS,
                render_steps: int = DEFAULT_RENDER_STEPS, bank_size: int = BANK_SIZE, directory=None,
                resume: bool = False, device="cpu", progress=None, cancel=None, seed: int = 0,
                keep_data: bool = False) -> dict:
    """Train (and index: the bank is written from the first ``bank_size`` examples when it is not
    current) one library graph; returns the metadata written next to the weights."""
    _, _, checkpoint = predictor_paths(name, directory)
    bank_size = min(bank_size, samples)
    if samples - bank_size < 8:
        raise OptionError(f"train {name}: --samples must exceed the bank's {bank_size} samples by at least 8")
    started = time.perf_counter()
    space = SampleSpace(name)
    space.graph.to(device)
    P, digest = space.num_params, graph_hash(name)
    config = {"bank_size": bank_size, "descriptor": DESCRIPTOR_KIND}  # examples are a prefix of the plan
    data = load_torch(checkpoint) if resume else None
    if data is not None and data.get("graph_sha256") == digest and data.get("config") == config:
        for key in ("thetas", "descriptors", "images", "seeds"):
            data[key] = data[key][:samples]
    else:
        data = {"graph_sha256": digest, "config": config, "thetas": torch.zeros(0, P),
                "descriptors": torch.zeros(0, DESCRIPTOR_DIM),
                "images": torch.zeros(0, 3, RENDER_SIZE, RENDER_SIZE).half(),
                "seeds": torch.zeros(0, dtype=torch.int64), "seconds": 0.0}
    plan = _plan(name, samples, bank_size)
    data = _generate(space, plan, data, checkpoint, device, progress, cancel)
    data_seconds = float(data["seconds"])
    if not bank_is_current(name, directory):
        write_bank(name, data["thetas"][:bank_size], data["descriptors"][:bank_size], list(range(bank_size)),
                   DESCRIPTOR_SIZE, BANK_SEED, directory)

    n_val = max(4, (samples - bank_size) // 8)
    idx = torch.arange(samples)
    train_idx, val_idx = idx[:-n_val], idx[-n_val:]
    x, y = data["descriptors"], data["thetas"]
    torch.manual_seed(seed)
    model = ParamPredictor(DESCRIPTOR_DIM, P)
    model.in_mean.copy_(x[train_idx].mean(0))
    model.in_std.copy_(x[train_idx].std(0).clamp_min(0.05))
    model.default.copy_(space.default)
    model.mask.copy_(space.mask)
    t1 = time.perf_counter()
    err_fit = fit_params(model, x[train_idx], y[train_idx], x[val_idx], y[val_idx], space.mask, epochs,
                          progress, cancel, seed)
    fit_seconds = time.perf_counter() - t1
    t2 = time.perf_counter()
    before = {k: v.clone() for k, v in model.state_dict().items()}
    if render_steps > 0:
        _render_phase(model, space.graph, data, train_idx, space.mask, render_steps, device, progress, cancel, seed)
    err_render = _val_error(model, x[val_idx], y[val_idx], space.mask)
    if err_render > err_fit * 1.02:  # the short style phase must not cost parameter accuracy
        model.load_state_dict(before)
    render_seconds = time.perf_counter() - t2
    # the figure that counts is that of the weights as stored (float16)
    model.load_state_dict({k: (v.half().float() if v.is_floating_point() else v)
                           for k, v in model.state_dict().items()})
    err = _val_error(model, x[val_idx], y[val_idx], space.mask)
    err_default = float(masked_l1(space.default.expand(n_val, -1), y[val_idx], space.mask))
    meta = {
        "graph": name, "graph_sha256": digest, "descriptor": DESCRIPTOR_KIND, "descriptor_dim": DESCRIPTOR_DIM,
        "format": PREDICTOR_FORMAT, "params": P, "sampled_params": int(space.mask.sum()), "sketch": SKETCH_DIM,
        "hidden": HIDDEN, "layers": LAYERS,
        "dtype": "float16", "training_samples": samples - n_val, "validation_samples": n_val,
        "bank_samples": bank_size, "epochs": epochs, "render_steps": render_steps, "render_size": RENDER_SIZE,
        "lambda_g": LAMBDA_G,
        "val_param_error": round(err, 5), "val_param_error_param_phase": round(err_fit, 5),
        "val_param_error_render_phase": round(err_render, 5), "val_param_error_default": round(err_default, 5),
        "render_phase_kept": err_render <= err_fit * 1.02,
        "seconds": {"data": round(data_seconds, 1), "fit": round(fit_seconds, 1), "render": round(render_seconds, 1),
                    "total": round(data_seconds + fit_seconds + render_seconds, 1)},
        "device": str(device), "torch_threads": torch.get_num_threads(),
    }
    save_predictor(model, name, meta, directory)
    if not keep_data:
        checkpoint.unlink(missing_ok=True)
    meta["wall_seconds"] = round(time.perf_counter() - started, 1)
    return meta
