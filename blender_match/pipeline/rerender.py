"""Re-rendering a fitted material (its params.json) at another size, without the photo (the
add-on's "re-render at 4K")."""
from __future__ import annotations

from pathlib import Path

from ..diffmat.params_file import load_params, read_params_file
from ..errors import ResultFolderError
from ..vocabulary import WRITING_MAPS
from .device import resolve_device
from .graphs import load_graph
from .options import check_size
from .progress import RENDER_SHARES, JobProgress
from .result_folder import MATCH_FILES, check_targets, write_result


def render_params(params_file, out_dir, size: int, device: str = "auto", overwrite: bool = False,
                  progress=None, cancel=None) -> dict:
    """Re-render a fitted material (its params.json) at ``size`` into ``out_dir``; returns the
    report written there."""
    params_file = Path(params_file)
    data = read_params_file(params_file)
    if not isinstance(data.get("source"), str):
        raise ResultFolderError(f"{params_file}: no \"source\" graph recorded (was it written by a match?)")
    size = check_size(size)
    torch_device = resolve_device(device)
    job = JobProgress(progress, cancel, RENDER_SHARES)
    graph = load_graph(data["source"])
    load_params(graph, params_file)
    check_targets(out_dir, graph.outputs, overwrite, MATCH_FILES)
    graph.to(torch_device)
    job.stage(WRITING_MAPS)
    return write_result(graph, data["source"], out_dir, size, int(data.get("seed", 0)), torch_device, overwrite, job,
                        report_extra={"rendered_from": str(params_file)})
