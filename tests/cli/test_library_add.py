"""``blender-match library add / list / remove`` end to end on a folder of real .sbs files: a user
graph gets its thumbnail and bank, is listed beside the shipped graphs, is chosen by automatic
ranking on a render of itself (also a graph whose look depends on its output size), a second run
resumes instead of redoing, and removal takes it out."""
from __future__ import annotations

import contextlib
import io
import json
import shutil

import pytest
import sbs_snippets as W
import torch

from blender_match.cli import main
from blender_match.diffmat.render import render_maps
from blender_match.library import load_library_graph, user_names
from blender_match.library.catalog import USER_LIBRARY_ENV
from blender_match.library.user import user_entry
from blender_match.selection.bank import SUPERSAMPLE_KEY, bank_is_current
from blender_match.selection.rank import NoSelectionModels, rank_graphs

USER_GRAPH = "synthoid_outputsizeexample"
GRAIN = "grain"  # Substance's White Noise as a base colour: a pixel-wide grain at every output size


@pytest.fixture(scope="module")
def added(tmp_path_factory, shared_dir):
    """A user library filled by ``library add FOLDER`` from a folder of one real .sbs and one
    broken file; the command's exit status and output, the library folder."""
    work = tmp_path_factory.mktemp("library-add")
    folder = work / "downloads"
    folder.mkdir()
    name = "synthoid_OutputSizeExample.sbs"
    shutil.copyfile(shared_dir / "data" / "sbs" / name, folder / name)
    (folder / "broken.sbs").write_text("<package>")
    (folder / "grain.sbs").write_text(W.white_noise_package())
    library = work / "library"
    patch = pytest.MonkeyPatch()
    patch.setenv(USER_LIBRARY_ENV, str(library))
    out = io.StringIO()  # capsys is per test; a module fixture reads the output itself
    with contextlib.redirect_stdout(out):
        status = main(["library", "add", str(folder)])
    yield {"status": status, "out": out.getvalue(), "library": library, "folder": folder}
    patch.undo()


@pytest.fixture()
def in_library(added, monkeypatch):
    monkeypatch.setenv(USER_LIBRARY_ENV, str(added["library"]))
    return added


def test_add_reports_each_file_and_refuses_the_broken_one(added):
    lines = added["out"].splitlines()
    assert added["status"] == 2  # one file refused
    assert lines[0] == f"user library: {added['library']}"
    assert any(line.startswith(f"{added['folder'] / 'broken.sbs'}: refused: ") and "malformed XML" in line
               for line in lines)
    assert any(line.startswith(f"{USER_GRAPH}: added (26 nodes") and "finer" not in line for line in lines)
    assert any(line.startswith(f"{GRAIN}: added (") and "seen from 4x finer renders" in line for line in lines)
    assert lines[-1] == "library add: 2 of 3 file(s) in the user library"


def test_the_added_graph_has_its_thumbnail_bank_and_listing(in_library, capsys):
    library = in_library["library"]
    assert user_names() == [GRAIN, USER_GRAPH]
    assert (library / "graphs" / f"{USER_GRAPH}.png").is_file()
    assert bank_is_current(USER_GRAPH)
    assert main(["library", "list", "--json"]) == 0
    listed = {e["name"]: e for e in json.loads(capsys.readouterr().out)}
    assert listed[USER_GRAPH]["library"] == "user" and listed["plaster"]["library"] == "built-in"
    assert listed[USER_GRAPH]["family"] is None and listed["plaster"]["family"] == "plaster"


def test_automatic_ranking_picks_the_user_graph_on_a_render_of_itself(in_library):
    graph = load_library_graph(USER_GRAPH)
    assert graph.name == USER_GRAPH  # not the graph's identifier in its package ("OutputSizeExample")
    with torch.no_grad():
        photo = render_maps(graph(size=256, seed=5)).clamp(0, 1)
    ranking = rank_graphs(photo, graphs=[USER_GRAPH, "plaster", "bricks", "painted_metal", "ceramic_tiles"])
    assert ranking[0]["graph"] == USER_GRAPH, [(e["graph"], round(e["distance"], 4)) for e in ranking]
    assert ranking[0]["start"] == "default"  # a render of its defaults: they beat the bank's nearest sample
    with pytest.raises(NoSelectionModels):  # no predictor was trained: only the bank (and the defaults) propose
        rank_graphs(photo, "predictor", graphs=[USER_GRAPH])


def test_a_graph_whose_look_depends_on_its_output_size_is_found_for_a_photo_of_itself(in_library):
    assert user_entry(GRAIN)[SUPERSAMPLE_KEY] == 4 and user_entry(USER_GRAPH)[SUPERSAMPLE_KEY] == 1
    with torch.no_grad():  # a match's photo is 512 px: the grain averages out to a soft grey at 128
        photo = render_maps(load_library_graph(GRAIN)(size=512, seed=5)).clamp(0, 1)
    ranking = rank_graphs(photo, graphs=[GRAIN, "plaster", "painted_wall", "glossy_paint", "sand"])
    assert ranking[0]["graph"] == GRAIN, [(e["graph"], round(e["distance"], 4)) for e in ranking]


def test_a_second_run_resumes_and_remove_takes_the_graph_out(in_library, capsys):
    sbs = in_library["folder"] / "synthoid_OutputSizeExample.sbs"
    bank = in_library["library"] / "models" / f"{USER_GRAPH}.bank.pt"
    bank.unlink()  # as if the first run was interrupted after the translation
    assert main(["library", "add", str(sbs)]) == 0
    assert f"{USER_GRAPH}: bank rebuilt" in capsys.readouterr().out and bank.is_file()
    assert main(["library", "add", str(sbs)]) == 0
    assert f"{USER_GRAPH}: up to date" in capsys.readouterr().out
    meta = in_library["library"] / "graphs" / f"{USER_GRAPH}.json"
    entry = json.loads(meta.read_text())
    meta.write_text(json.dumps({k: v for k, v in entry.items() if k != SUPERSAMPLE_KEY}))  # an older add
    assert main(["library", "add", str(sbs)]) == 0
    assert f"{USER_GRAPH}: added" in capsys.readouterr().out and user_entry(USER_GRAPH) == entry
    assert main(["library", "remove", USER_GRAPH]) == 0
    assert user_names() == [GRAIN] and not bank.exists()
    assert main(["library", "remove", USER_GRAPH]) == 2
    assert f"{USER_GRAPH}: not in the user library" in capsys.readouterr().err
