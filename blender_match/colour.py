"""The sRGB transfer curve (IEC 61966-2-1), defined once. Standard library only: the engine applies
it to tensors (``diffmat.render``), the add-on to numpy arrays in Blender's Python, which has no
torch (``blender.material_builder``); each writes the two-branch formula with its own ``where``:

    linear  = encoded / SRGB_SLOPE                                   if encoded <= SRGB_KNEE
              ((encoded + SRGB_OFFSET) / SRGB_SCALE) ** SRGB_GAMMA   otherwise
    encoded = linear * SRGB_SLOPE                                    if linear <= LINEAR_KNEE
              SRGB_SCALE * linear ** (1 / SRGB_GAMMA) - SRGB_OFFSET  otherwise
"""
from __future__ import annotations

SRGB_KNEE = 0.04045       # encoded value where the linear segment meets the power curve
LINEAR_KNEE = 0.0031308   # about the same point in linear light (SRGB_KNEE / SRGB_SLOPE)
SRGB_SLOPE = 12.92        # slope of the linear segment
SRGB_OFFSET = 0.055       # the power curve's offset
SRGB_SCALE = 1.055        # 1 + SRGB_OFFSET
SRGB_GAMMA = 2.4          # the power curve's exponent
