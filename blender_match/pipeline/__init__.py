"""The matching pipeline that the CLI (``blender-match match``), the worker process and the
benchmarks share: photo in, fitted procedural material out, as files in one folder or in memory.

``match_photo(photo, out_dir, options, progress, cancel)`` reads the photo, fits the graph
(``options.graph``; None: automatic selection), evaluates the fitted graph at ``options.size``
and writes the result folder (``result_folder``), atomically; ``fit_photo(photo, options)`` does
the same fit and returns it (a ``Match``) without writing. ``render_params(params_file, out_dir,
size)`` re-renders a fitted material at another size without the photo.

``progress(event)`` receives dicts: ``stage`` (one of ``vocabulary.STAGES``), ``fraction`` of the
whole job in [0, 1], ``eta_seconds`` (or None), and while fitting ``graph``, ``graph_index``,
``graph_count``, ``iteration``, ``iterations``, ``loss``. ``cancel()`` is polled at least once per
iteration; when it returns True the job stops with ``errors.Cancelled`` and writes nothing.

Modules: ``options`` (MatchOptions, their checks, quality -> Schedule), ``device``, ``graphs``
(loading the graph a match names), ``progress``, ``match`` (the flow), ``result_folder``,
``rerender``.
"""
from .device import resolve_device
from .graphs import load_graph
from .match import Match, finish_calibration, fit_named_graph, fit_photo, match_photo, photo_loss
from .options import AUTO_CANDIDATES, PHOTO_SIZE, MatchOptions, check_size, match_schedule
from .rerender import render_params
from .result_folder import MatchFailed

__all__ = ["AUTO_CANDIDATES", "PHOTO_SIZE", "Match", "MatchFailed", "MatchOptions", "check_size", "finish_calibration",
           "fit_named_graph", "fit_photo", "load_graph", "match_photo", "match_schedule", "photo_loss",
           "render_params", "resolve_device"]
