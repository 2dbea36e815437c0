"""The sample bank: graph selection and a starting point without any training.

For each library graph, the bank holds the compact descriptors (``selection.descriptor``) of N
random variants of the graph (``sample_params(name, k)``, k = 0..N-1, rendered at 128 px under
the flash with graph seed ``BANK_SEED``) together with their normalised parameter vectors. A
photo's nearest sample (``nearest``) gives, per graph, how close the graph can come to the photo
without fitting and the parameters that came closest: a start for the fit. Adding a graph only
adds its bank; nothing else is recomputed.

Files: ``<name>.bank.pt`` in the models folder of the graph's library (``library/models/`` for the
shipped graphs), a ``torch.save`` of plain tensors, strings and numbers
(``torch.load(..., weights_only=True)`` reads it): the descriptors (N, D) quantised to 8 bits
per value between each dimension's lowest and highest value over the bank (``codes`` uint8,
``low`` and ``step`` (D,) float32: a step is about 1/255 of a spread of a few log units, far
below the differences between samples, and the file is a quarter of float32), ``thetas`` (N, P)
float32, ``indices`` (the sample indices k), and what makes it current: the SHA-256 of the
graph's ``.sbs``, its ``.json`` and the engine's render revision (``graph_hash``), the
descriptor kind and the file's ``format``; and the render size and seed. ``load_bank`` returns
the descriptors decoded, as ``descriptors`` (N, D) float32.

This module also holds what the bank and the predictor's training share: the models folder,
the staleness hash, parameter vectors of samples and rendering + describing them, and how finely a
graph is rendered to be described (``supersample``): a graph is rendered at the description's size
times its ``SUPERSAMPLE_KEY`` (1 unless its metadata says otherwise) and brought down. Most graphs
look the same rendered at 128 px as rendered at a match's 512 and brought down to 128: their
structure is drawn relative to the texture. Some production graphs are not: a grain a pixel wide at
every output size (a Substance white noise through levels) is a contrasty pixel noise at 128 and a
soft tone at 512 brought down, so described from 128-px renders such a graph is not even
shortlisted for a photo of itself. ``library add`` measures this at the graph's defaults
(``measured_supersample``) and records the factor; the bank, the predictor's examples and the
ranking all render the graph that finely (docs/matching.md).
"""
from __future__ import annotations

import hashlib
import io
import random
from pathlib import Path

import torch

from ..diffmat.optim import resize_square
from ..diffmat.render import render_maps
from ..diffmat.revision import RENDER_REVISION
from ..library import (
    apply_params,
    library_entry,
    library_path,
    load_library_graph,
    metadata_file,
    models_folder,
    sample_params,
)
from ..safe_files import write_atomic
from .descriptor import DESCRIPTOR_KIND, DESCRIPTOR_SIZE, compact_descriptor, descriptor_distance, shared_vgg

BANK_SIZE = 64
BANK_SEED = 0
BANK_SUFFIX = ".bank.pt"
BANK_FORMAT = 2  # raised when the file's layout changes: older files are stale
SUPERSAMPLE_KEY = "selection_supersample"  # a graph's metadata: its render size over the description's
# A graph is rendered finer for selection when its look at the description's size and brought down
# from a match's size differ by more than SIZE_DEPENDENCE times what another noise seed changes, at
# least SEED_SPREAD_FLOOR: the low end of that seed spread over 100 public production graphs, whose
# median is 0.27 in ``descriptor_distance`` units (docs/matching.md).
SIZE_DEPENDENCE = 2.0
SEED_SPREAD_FLOOR = 0.2


def models_dir(path, name: str) -> Path:
    """The folder of graph ``name``'s models: ``path`` when given, else its library's own."""
    return Path(path) if path is not None else models_folder(name)


def graph_hash(name: str) -> str:
    """SHA-256 of a library graph's .sbs file, its metadata (the translated parameter space,
    sampling ranges) and the engine's render revision: a model built before any of them changed
    is stale, so a translator change that moves the parameter vector retrains the graphs it
    touches, and an engine change that moves their looks retrains them all."""
    revision = f"render revision {RENDER_REVISION}".encode()
    return hashlib.sha256(library_path(name).read_bytes() + metadata_file(name).read_bytes() + revision).hexdigest()


def save_torch(obj, path: Path):
    """torch.save through an atomic write (a reader never sees half a file)."""
    buffer = io.BytesIO()
    torch.save(obj, buffer)
    write_atomic(Path(path), buffer.getvalue(), overwrite=True)


def load_torch(path: Path):
    """A file written by ``save_torch``, read with weights_only=True; None when absent."""
    path = Path(path)
    if not path.is_file():
        return None
    return torch.load(path, map_location="cpu", weights_only=True)


class SampleSpace:
    """A library graph's parameter vectors: the default, which components the library samples
    (``mask``) and the normalised vector of any sample ``k`` (optionally jittered)."""

    def __init__(self, name: str, graph=None):
        self.name = name
        self.graph = graph if graph is not None else load_library_graph(name)
        self.default = self.graph.get_vector().clone()
        keys = set(library_entry(name)["sample_ranges"])
        names = self.graph.param_names()
        self.mask = torch.tensor([n.split("[")[0] in keys for n in names], dtype=torch.bool)

    @property
    def num_params(self) -> int:
        return self.default.numel()

    def vector(self, k: int) -> torch.Tensor:
        """The normalised (P,) vector of ``sample_params(name, k)`` (other parameters: default)."""
        self.graph.set_vector(self.default)
        apply_params(self.graph, sample_params(self.name, k))
        theta = self.graph.get_vector().clone()
        self.graph.set_vector(self.default)
        return theta

    def jittered(self, k: int, rng: random.Random, amount: float) -> torch.Tensor:
        """Sample k moved by up to ``amount`` (uniform, normalised units) on every sampled
        component, clamped to [0, 1]: variants just outside the declared ranges."""
        theta = self.vector(k)
        noise = torch.tensor([rng.uniform(-amount, amount) for _ in range(theta.numel())])
        return torch.where(self.mask, (theta + noise).clamp(0, 1), theta)


def supersample(entry: dict) -> int:
    """How many times the description's size the library graph of metadata ``entry``
    (``library_entry``) is rendered at for selection (its ``SUPERSAMPLE_KEY``; 1 when it has none)."""
    return int(entry.get(SUPERSAMPLE_KEY, 1))


def render_images(graph, thetas: torch.Tensor, seed: int, size: int, factor: int = 1) -> torch.Tensor:
    """Flash renders (N, 3, size, size) of normalised parameter vectors (N, P), graph seed ``seed``:
    rendered at ``factor`` x ``size`` and brought down to ``size`` (antialiased) when ``factor`` > 1."""
    with torch.no_grad():
        images = render_maps(graph(size=size * factor, seed=seed, theta=thetas)).clamp(0, 1)
    if images.shape[0] != thetas.shape[0]:
        images = images.expand(thetas.shape[0], -1, -1, -1)
    return resize_square(images, size)


def measured_supersample(graph, factor: int, device="cpu") -> int:
    """``factor`` when the graph (at its own parameters) described from a render ``factor`` times
    the description's size, brought down, differs from its plain render's description by more than
    ``SIZE_DEPENDENCE`` times what another noise seed changes (that change counted as at least
    ``SEED_SPREAD_FLOOR``, so that a graph without noise is not flagged for a trifle); else 1."""
    theta = graph.get_vector()[None].to(device)
    plain, other_seed, fine = (describe(render_images(graph, theta, seed, DESCRIPTOR_SIZE, f), device)
                               for seed, f in ((0, 1), (1, 1), (0, factor)))
    by_size = float(descriptor_distance(plain, fine)[0, 0])
    by_seed = max(float(descriptor_distance(plain, other_seed)[0, 0]), SEED_SPREAD_FLOOR)
    graph.clear_cache()
    return factor if by_size > SIZE_DEPENDENCE * by_seed else 1


def describe(images: torch.Tensor, device="cpu", size: int = DESCRIPTOR_SIZE) -> torch.Tensor:
    with torch.no_grad():
        return compact_descriptor(shared_vgg(device), images.to(device), size).cpu()


DEFAULTS_INDEX = -1  # a bank row's sample index when the row is the graph's own defaults


def build_bank(name: str, n: int = BANK_SIZE, size: int = DESCRIPTOR_SIZE, seed: int = BANK_SEED,
               directory=None, device="cpu", progress=None, batch: int = 8, with_defaults: bool = False) -> Path:
    """Render (``supersample`` times finer, brought down) and describe at ``size`` samples 0..n-1
    of a library graph and write its bank file; ``with_defaults`` puts the graph's own defaults
    first (index ``DEFAULTS_INDEX``).
    ``progress(done, total)`` after every batch."""
    space = SampleSpace(name)
    graph = space.graph.to(device)
    factor = supersample(library_entry(name))
    indices = ([DEFAULTS_INDEX] if with_defaults else []) + list(range(n))
    thetas = torch.stack([space.default.clone() if k == DEFAULTS_INDEX else space.vector(k) for k in indices])
    descriptors = []
    for start in range(0, len(indices), batch):
        images = render_images(graph, thetas[start:start + batch].to(device), seed, size, factor)
        descriptors.append(describe(images, device, size))
        if progress is not None:
            progress(min(len(indices), start + batch), len(indices))
    graph.clear_cache()
    return write_bank(name, thetas, torch.cat(descriptors), indices, size, seed, directory)


def bank_path(name: str, directory=None) -> Path:
    return models_dir(directory, name) / f"{name}{BANK_SUFFIX}"


def write_bank(name: str, thetas: torch.Tensor, descriptors: torch.Tensor, indices: list[int], size: int,
               seed: int, directory=None) -> Path:
    path = bank_path(name, directory)
    descriptors = descriptors.float().cpu()
    low = descriptors.min(0).values
    step = ((descriptors.max(0).values - low) / 255).clamp_min(1e-6)
    codes = ((descriptors - low) / step).round().clamp(0, 255).to(torch.uint8)
    save_torch({"graph": name, "graph_sha256": graph_hash(name), "descriptor": DESCRIPTOR_KIND,
                "format": BANK_FORMAT, "size": int(size), "seed": int(seed),
                "indices": torch.tensor(indices, dtype=torch.int64), "thetas": thetas.float().cpu(),
                "codes": codes, "low": low, "step": step}, path)
    return path


def load_bank(name: str, directory=None) -> dict | None:
    """A graph's bank, its descriptors decoded (None when it has none, or one of an older format)."""
    bank = load_torch(bank_path(name, directory))
    if bank is None or bank.get("format") != BANK_FORMAT:
        return None
    bank["descriptors"] = bank["codes"].float() * bank["step"] + bank["low"]
    return bank


def current_bank(name: str, directory=None) -> dict | None:
    """A graph's bank when it is current (built from this .sbs/.json, with this descriptor), else
    None: one read for the check and the use."""
    bank = load_bank(name, directory)
    if bank is None or bank.get("graph_sha256") != graph_hash(name) or bank.get("descriptor") != DESCRIPTOR_KIND:
        return None
    return bank


def bank_is_current(name: str, directory=None) -> bool:
    return current_bank(name, directory) is not None


def nearest(bank: dict, descriptor: torch.Tensor, count: int = 1) -> list[dict]:
    """The ``count`` samples of the bank closest to one descriptor (D,) or (1, D), best first:
    {"distance", "theta" (P,), "index" (the sample k)}."""
    distances = descriptor_distance(descriptor.reshape(1, -1), bank["descriptors"])[0]
    order = torch.argsort(distances)[:count]
    return [{"distance": float(distances[i]), "theta": bank["thetas"][i].clone(), "index": int(bank["indices"][i])}
            for i in order]
