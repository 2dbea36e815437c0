"""The one exception type the engine raises for bad input.

Every message names the offending thing (node, parameter, file) and the problem on one line, so
the CLI and the Blender add-on can show it as it is.
"""

from ..errors import BlenderMatchError


class DiffMatError(BlenderMatchError):
    """Bad input to the DiffMat engine: a wrong shape, an unknown mode, a value out of range."""
