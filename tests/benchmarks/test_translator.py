"""``bench translator`` over a folder: every file gets a row, a broken one its error, and the last
row counts the files translated and rendered."""
from __future__ import annotations

import json

import pytest
import sbs_snippets as W

from blender_match.benchmarks import translator


def _good_package() -> str:
    nodes = [W.filter_node(5, "uniform", params=[W.param("outputcolor", "constantValueFloat4", "0.3 0.5 0.7 1")],
                           outputs=[(6, 1)]),
             W.output_node(20, 100, 5, 6)]
    return W.package([W.graph("G", nodes, outputs=[(100, "c", "baseColor")])])


def test_a_folder_is_swept_and_a_broken_file_is_a_row(tmp_path):
    (tmp_path / "sub").mkdir()
    (tmp_path / "sub" / "good.sbs").write_text(_good_package())
    (tmp_path / "broken.sbs").write_text("<package><content>")
    (tmp_path / "notes.txt").write_text("not a package")
    rows = translator.run(files=[tmp_path], repeats=1, out=tmp_path / "out")
    by_file = {r["file"]: r for r in rows[:-1]}
    assert set(by_file) == {"good.sbs", "broken.sbs"}
    assert by_file["good.sbs"]["rendered"] is True and by_file["good.sbs"]["native"] == 1
    assert by_file["broken.sbs"]["rendered"] is False
    assert "broken.sbs" in by_file["broken.sbs"]["error"]
    assert rows[-1]["file"] == "all: 2 files"
    assert (rows[-1]["nodes"], rows[-1]["rendered"], rows[-1]["error"]) == ("1 translated", "1 rendered", "1 failed")
    saved = json.loads((tmp_path / "out" / "results.json").read_text(encoding="utf-8"))
    assert saved["summary"] == {"files": 2, "translated": 1, "rendered": 1}
    assert saved["config"]["files"] == [str(tmp_path)] and len(saved["rows"]) == 2
    assert "| 2 | 1 | 1 |" in (tmp_path / "out" / "results.md").read_text(encoding="utf-8")


def test_a_folder_without_packages_is_named(tmp_path):
    with pytest.raises(FileNotFoundError, match=str(tmp_path)):
        translator.run(files=[tmp_path], repeats=1)
