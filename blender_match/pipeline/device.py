"""The torch device a device name (``vocabulary.DEVICES``) stands for on this machine."""
from __future__ import annotations

import torch

from ..errors import OptionError
from ..vocabulary import DEVICE_NAMES


def _mps_available() -> bool:
    mps = getattr(torch.backends, "mps", None)
    return mps is not None and mps.is_available()


def resolve_device(name: str) -> torch.device:
    """The torch device for "auto", "cpu", "cuda" or "mps" (OptionError when it is absent)."""
    if name not in DEVICE_NAMES:
        raise OptionError(f"device {name!r}: expected one of {', '.join(DEVICE_NAMES)}")
    if name == "auto":
        if torch.cuda.is_available():
            return torch.device("cuda")
        return torch.device("mps" if _mps_available() else "cpu")
    if name == "cuda" and not torch.cuda.is_available():
        raise OptionError("device cuda: no CUDA GPU is available to this torch")
    if name == "mps" and not _mps_available():
        raise OptionError("device mps: Metal is not available to this torch")
    return torch.device(name)
