"""``blender-match bench``: each suite takes the options its ``run`` names, and refuses another in
one line instead of dropping it or stopping with a traceback."""
from __future__ import annotations

import importlib
import json

import pytest

from blender_match.cli import main
from blender_match.cli.bench import OPTION_FLAGS, SUITES, suite_options


def test_every_suite_option_is_taken_by_some_suite_and_every_flag_is_known():
    taken = {what: suite_options(importlib.import_module(f"blender_match.benchmarks.{what}").run) for what in SUITES}
    assert set(OPTION_FLAGS) <= set().union(*taken.values())  # no flag that no suite reads
    assert taken["translator"] & set(OPTION_FLAGS) == {"files", "out"}
    assert taken["ranking"] & set(OPTION_FLAGS) == {"photos", "out"}
    assert not taken["nodes"] & set(OPTION_FLAGS)


@pytest.mark.parametrize("argv, refused, listed", [
    (["translator", "--quick"], "--quick", "--files, --out"),
    (["ranking", "--zoom", "2"], "--zoom", "--photos, --out"),
    (["selection", "--out", "OUT"], "--out", "--graphs"),
    (["nodes", "--graphs", "plaster"], "--graphs", "none of the suites' options"),
])
def test_an_option_the_suite_does_not_take_is_refused_in_one_line(argv, refused, listed, capsys, tmp_path):
    argv = [str(tmp_path / "out") if a == "OUT" else a for a in argv]
    assert main(["bench", *argv]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1, err
    assert f"bench {argv[0]} does not take {refused};" in err and listed in err
    assert not (tmp_path / "out").exists()


def test_bench_translator_out_writes_its_results(tmp_path, shared_dir):
    """The report that stopped with a traceback: ``bench translator --files … --out DIR``."""
    package = sorted((shared_dir / "data" / "sbs").glob("*.sbs"))[0]
    assert main(["bench", "translator", "--files", str(package), "--out", str(tmp_path / "out")]) == 0
    saved = json.loads((tmp_path / "out" / "results.json").read_text(encoding="utf-8"))
    assert saved["summary"] == {"files": 1, "translated": 1, "rendered": 1}
    assert (tmp_path / "out" / "results.md").is_file()
