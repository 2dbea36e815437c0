"""Progress bars of the ``blender-match`` commands: tqdm bars on stderr, drawn only when stderr is
a terminal (tqdm's ``disable=None``), so that what is piped or logged holds the results alone."""
from __future__ import annotations

import sys

from tqdm import tqdm


def progress_bar(total: float, description: str = "", bar_format: str | None = None) -> tqdm:
    """A bar on stderr redrawn at most four times a second, left on screen when closed."""
    return tqdm(total=total, desc=description, bar_format=bar_format, file=sys.stderr, disable=None,
                mininterval=0.25, dynamic_ncols=True, leave=True)
