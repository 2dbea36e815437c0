"""``blender-match build-extension``: the zip Blender installs, built and validated with Blender's
own extension tool, then installed, enabled, used and removed in the real bpy module."""
from __future__ import annotations

import json
import os
import re
import subprocess
import sys
import textwrap
import tomllib
import zipfile
from pathlib import Path

import pytest
from conftest import ROOT

from blender_match.cli import main
from blender_match.cli.build_extension import blender_ext_tool


@pytest.fixture(scope="module")
def built_zip(tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("dist")
    assert main(["build-extension", "--out", str(out)]) == 0
    [zip_path] = out.glob("*.zip")
    return zip_path


def test_zip_holds_the_manifest_the_package_and_its_data(built_zip):
    manifest = tomllib.loads((ROOT / "blender_manifest.toml").read_text())
    assert built_zip.name == f"blender_match-{manifest['version']}.zip"
    assert manifest["id"] == "blender_match" and manifest["license"] == ["SPDX:GPL-3.0-or-later"]
    assert set(manifest["permissions"]) == {"files", "network"}
    names = set(zipfile.ZipFile(built_zip).namelist())
    assert {"blender_manifest.toml", "__init__.py", "pipeline/__init__.py", "vocabulary.py", "errors.py"} <= names
    assert {"worker/__init__.py", "worker/__main__.py", "worker/client.py", "worker/protocol.py",
            "worker/backend_setup.py"} <= names
    assert {"library/graphs/plaster.sbs", "library/graphs/plaster.json"} <= names
    assert any(n.startswith("diffmat/") for n in names) and any(n.startswith("translator/") for n in names)
    assert not [n for n in names if "__pycache__" in n or n.endswith(".pyc") or n.startswith(".")]
    packaged = {p.relative_to(ROOT / "blender_match").as_posix() for p in (ROOT / "blender_match").rglob("*.sbs")}
    assert packaged <= names


def test_the_zip_passes_blender_s_validation(built_zip):
    result = subprocess.run([sys.executable, str(blender_ext_tool()), "validate", str(built_zip)],
                            capture_output=True, text=True, timeout=120)
    assert result.returncode == 0, result.stdout + result.stderr


def test_existing_zip_is_kept_unless_overwrite(built_zip, capsys):
    before = built_zip.stat().st_mtime_ns
    assert main(["build-extension", "--out", str(built_zip.parent)]) == 2
    assert "already exists (use --overwrite" in capsys.readouterr().err
    assert built_zip.stat().st_mtime_ns == before
    assert main(["build-extension", "--out", str(built_zip.parent), "--overwrite"]) == 0
    assert capsys.readouterr().out.strip() == str(built_zip)
    assert zipfile.ZipFile(built_zip).testzip() is None
    assert [p.name for p in built_zip.parent.iterdir()] == [built_zip.name]  # no leftovers


def test_check_validates_without_building(tmp_path, capsys):
    assert main(["build-extension", "--check"]) == 0
    assert "valid extension" in capsys.readouterr().out
    bad = tmp_path / "blender_manifest.toml"
    text = (ROOT / "blender_manifest.toml").read_text()
    bad.write_text(re.sub(r'(?m)^tagline = .*$', 'tagline = "Ends with a full stop."', text))
    assert main(["build-extension", "--check", "--manifest", str(bad)]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("blender-match: error: extension validation failed: ")
    assert "tagline" in err and "punctuation" in err and "\n" not in err
    assert main(["build-extension", "--out", str(tmp_path / "dist"), "--manifest", str(bad)]) == 2
    assert not (tmp_path / "dist").exists() or not list((tmp_path / "dist").iterdir())


def test_check_refuses_a_manifest_that_disagrees_with_the_package(tmp_path, capsys):
    other = tmp_path / "blender_manifest.toml"
    other.write_text(re.sub(r'(?m)^version = "', 'version = "9', (ROOT / "blender_manifest.toml").read_text()))
    assert main(["build-extension", "--check", "--manifest", str(other)]) == 2
    assert "differs from blender_match" in capsys.readouterr().err
    assert main(["build-extension"]) == 2
    assert "give --out DIR" in capsys.readouterr().err


INSTALL = textwrap.dedent("""
    import json, os, sys
    from pathlib import Path
    import bpy
    import addon_utils

    ZIP, RES = sys.argv[1], Path(os.environ["BLENDER_USER_RESOURCES"])
    MOD = "bl_ext.user_default.blender_match"
    out = {}
    types_before = set(dir(bpy.types))
    out["install"] = sorted(bpy.ops.extensions.package_install_files(
        filepath=ZIP, repo="user_default", enable_on_install=True))
    out["enabled"] = MOD in bpy.context.preferences.addons
    out["loaded"] = list(addon_utils.check(MOD))
    installed = RES / "extensions" / "user_default" / "blender_match"
    out["installed"] = sorted(p.name for p in installed.iterdir())
    out["torch_after_enable"] = "torch" in sys.modules

    # The installed add-on starts its worker from the extension's own folder.
    import importlib
    client = importlib.import_module(MOD + ".worker.client")
    protocol = importlib.import_module(MOD + ".worker.protocol")
    out["package_root"] = str(client.PACKAGE_ROOT)
    job = client.WorkerJob(sys.executable, protocol.probe_request())
    job.wait(timeout=180)
    out["probe"] = {"state": job.state, "error": job.error_message, "report": job.result}
    out["torch_after_probe"] = "torch" in sys.modules

    bpy.ops.preferences.addon_disable(module=MOD)
    out["enabled_after_disable"] = MOD in bpy.context.preferences.addons
    out["uninstall"] = sorted(bpy.ops.extensions.package_uninstall(
        repo_directory=str(installed.parent), pkg_id="blender_match"))
    out["left_on_disk"] = installed.exists()
    out["new_types"] = sorted(set(dir(bpy.types)) - types_before)
    print("RESULT " + json.dumps(out))
""")


@pytest.mark.bpy
def test_install_enable_use_and_uninstall_in_blender(built_zip, tmp_path):
    env = {**os.environ, "BLENDER_USER_RESOURCES": str(tmp_path / "blender-user")}
    result = subprocess.run([sys.executable, "-c", INSTALL, str(built_zip)], cwd=tmp_path, env=env,
                            capture_output=True, text=True, timeout=600)
    assert result.returncode == 0, result.stdout[-2000:] + result.stderr[-4000:]
    [line] = [text for text in result.stdout.splitlines() if text.startswith("RESULT ")]
    out = json.loads(line[len("RESULT "):])
    assert out["install"] == ["FINISHED"]
    assert out["enabled"] and out["loaded"] == [True, True]
    assert {"__init__.py", "blender_manifest.toml", "worker", "library", "diffmat"} <= set(out["installed"])
    assert not out["torch_after_enable"]
    installed = tmp_path / "blender-user" / "extensions" / "user_default"
    assert Path(out["package_root"]) == installed
    probe = out["probe"]
    assert probe["state"] == "finished", probe["error"]
    assert Path(probe["report"]["package"]) == installed / "blender_match"  # the installed copy ran
    assert probe["report"]["torch"]
    assert not out["torch_after_probe"]  # torch stayed in the worker
    assert not out["enabled_after_disable"]
    assert out["uninstall"] == ["FINISHED"] and not out["left_on_disk"]
    assert out["new_types"] == []  # nothing left registered
