"""Stateless functional ops of DiffMat (like ``torch.nn.functional``).

Every public name in a submodule's ``__all__`` is re-exported here, so ``F.levels`` or
``F.perlin_noise`` is one attribute away. Submodules hold one family of ops each (``common`` holds
shared helpers and exports nothing). The re-exports are written out as star imports of each
family's ``__all__`` so that static checkers (and readers) see where every name comes from.
"""
# ruff: noqa: F403 -- each family's ``__all__`` is its public interface, re-exported whole
from . import basic as _basic
from . import blend as _blend
from . import blur as _blur
from . import distance as _distance
from . import function_graph as _function_graph
from . import fxmap as _fxmap
from . import gradient_map as _gradient_map
from . import inputs as _inputs
from . import library_adjust as _library_adjust
from . import library_blur as _library_blur
from . import library_normal as _library_normal
from . import noise_generators as _noise_generators
from . import noise_grunge as _noise_grunge
from . import noise_primitives as _noise_primitives
from . import pattern_cells as _pattern_cells
from . import pattern_shapes as _pattern_shapes
from . import pattern_tiles as _pattern_tiles
from . import processor as _processor
from . import relief as _relief
from . import tone as _tone
from . import transform as _transform
from . import warp as _warp
from .basic import *
from .blend import *
from .blur import *
from .distance import *
from .function_graph import *
from .fxmap import *
from .gradient_map import *
from .inputs import *
from .library_adjust import *
from .library_blur import *
from .library_normal import *
from .noise_generators import *
from .noise_grunge import *
from .noise_primitives import *
from .pattern_cells import *
from .pattern_shapes import *
from .pattern_tiles import *
from .processor import *
from .relief import *
from .tone import *
from .transform import *
from .warp import *

__all__: list[str] = [
    *_basic.__all__,
    *_blend.__all__,
    *_blur.__all__,
    *_distance.__all__,
    *_function_graph.__all__,
    *_fxmap.__all__,
    *_gradient_map.__all__,
    *_inputs.__all__,
    *_library_adjust.__all__,
    *_library_blur.__all__,
    *_library_normal.__all__,
    *_noise_generators.__all__,
    *_noise_grunge.__all__,
    *_noise_primitives.__all__,
    *_pattern_cells.__all__,
    *_pattern_shapes.__all__,
    *_pattern_tiles.__all__,
    *_processor.__all__,
    *_relief.__all__,
    *_tone.__all__,
    *_transform.__all__,
    *_warp.__all__,
]
