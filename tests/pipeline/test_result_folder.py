"""Result folders: a graph with the optional anisotropy maps (written, flat, refused), and the JSON files."""
from __future__ import annotations

import json

import pytest

from blender_match.library import load_library_graph
from blender_match.pipeline.progress import RENDER_SHARES, JobProgress
from blender_match.pipeline.result_folder import COMPARISON_TILE, check_targets, write_result
from blender_match.safe_files import FileWriteError
from blender_match.vocabulary import (
    ANISOTROPY,
    ANISOTROPY_ANGLE,
    AUTHORED_USAGES,
    PARAMS_FILE,
    REPORT_FILE,
    WRITING_MAPS,
)

PNG_DEPTH, PNG_COLOR_TYPE, GRAY = 24, 25, 0


def test_an_anisotropic_graph_writes_its_level_and_angle_as_flat_grey_maps(tmp_path):
    """brushed_metal's level (its exposed ``anisotropy``, 0.6) and angle (0) are constants: the
    report says so, which the material builder turns into values instead of textures."""
    graph = load_library_graph("brushed_metal")
    job = JobProgress(None, None, RENDER_SHARES)
    job.stage(WRITING_MAPS)
    report = write_result(graph, "brushed_metal", tmp_path, 32, 0, "cpu", False, job)
    assert report["maps"][ANISOTROPY] == {"file": "anisotropylevel.png", "flat": [0.6]}
    assert report["maps"][ANISOTROPY_ANGLE] == {"file": "anisotropyangle.png", "flat": [0.0]}
    for usage in (ANISOTROPY, ANISOTROPY_ANGLE):
        data = (tmp_path / f"{usage}.png").read_bytes()
        assert (data[PNG_DEPTH], data[PNG_COLOR_TYPE]) == (8, GRAY)
    comparison = (tmp_path / "comparison.png").read_bytes()
    width = int.from_bytes(comparison[16:20], "big")
    assert width == COMPARISON_TILE * (2 + len(AUTHORED_USAGES))  # the render, the authored maps, the level
    with pytest.raises(FileWriteError, match="anisotropylevel.png"):
        check_targets(tmp_path, [ANISOTROPY], overwrite=False, extra=())


def test_the_params_and_report_files_are_json_text_ending_in_a_newline(tmp_path):
    """A text file a user opens, diffs or appends to ends its last line (stop 44: they did not)."""
    job = JobProgress(None, None, RENDER_SHARES)
    job.stage(WRITING_MAPS)
    report = write_result(load_library_graph("plaster"), "plaster", tmp_path, 32, 0, "cpu", False, job)
    for name in (PARAMS_FILE, REPORT_FILE):
        text = (tmp_path / name).read_text(encoding="utf-8")
        assert text.endswith("}\n") and not text.endswith("\n\n")
    assert json.loads((tmp_path / REPORT_FILE).read_text())["graph"] == report["graph"] == "plaster"
    assert json.loads((tmp_path / PARAMS_FILE).read_text())["graph"] == "plaster"
