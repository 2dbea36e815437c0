"""``blender-match build-extension --out DIR``: package the add-on as a Blender extension (.zip).

Stages ``blender_manifest.toml`` (the repository's) and the ``blender_match`` package (without
caches) in a temporary folder, validates it and builds the zip with Blender's own extension tool
(``blender_ext.py``, shipped with the ``bpy`` module), then prints the zip's path. ``--check``
only validates. The zip installs with Blender > Preferences > Get Extensions > Install from Disk,
or ``blender --command extension install-file -r user_default ZIP``.
"""
from __future__ import annotations

import importlib.util
import json
import os
import shutil
import subprocess
import sys
import tempfile
import tomllib
from pathlib import Path

from ..errors import OptionError
from ..version import __version__

PACKAGE_DIR = Path(__file__).resolve().parents[1]
MANIFEST = PACKAGE_DIR.parent / "blender_manifest.toml"
EXCLUDE = ("__pycache__", "*.pyc", "*.pyo", ".*", "*.zip", "*.egg-info")


def add_parser(sub):
    p = sub.add_parser("build-extension", help="package the add-on as a Blender extension zip")
    p.add_argument("--out", type=Path, help="folder to write blender_match-VERSION.zip into")
    p.add_argument("--check", action="store_true", help="only validate the manifest and package")
    p.add_argument("--manifest", type=Path, default=MANIFEST,
                   help="the extension manifest (default: blender_manifest.toml next to the package)")
    p.add_argument("--overwrite", action="store_true", help="replace an existing zip")
    p.set_defaults(run=run)


def blender_ext_tool() -> Path:
    """Blender's extension command-line tool inside the installed bpy module."""
    spec = importlib.util.find_spec("bpy")
    if spec is None or not spec.origin:
        raise OptionError("build-extension needs the bpy module for Blender's extension tool "
                         "(pip install 'blender-match[blender]')")
    found = sorted(Path(spec.origin).parent.glob("*/scripts/addons_core/bl_pkg/cli/blender_ext.py"))
    if not found:
        raise OptionError(f"{Path(spec.origin).parent}: Blender's extension tool (blender_ext.py) not found in bpy")
    return found[-1]


def read_manifest(path: Path) -> dict:
    try:
        manifest = tomllib.loads(path.read_text(encoding="utf-8"))
    except FileNotFoundError:
        raise FileNotFoundError(f"{path}: extension manifest not found (build from a source checkout, "
                                "or give --manifest)") from None
    except tomllib.TOMLDecodeError as exc:
        raise OptionError(f"{path}: not valid TOML ({exc})") from None
    if manifest.get("id") != PACKAGE_DIR.name:
        raise OptionError(f"{path}: id {manifest.get('id')!r} must be the package's name {PACKAGE_DIR.name!r} "
                         "(the worker imports the installed folder by that name)")
    if manifest.get("version") != __version__:
        raise OptionError(f"{path}: version {manifest.get('version')!r} differs from blender_match "
                         f"{__version__} (update one of them)")
    return manifest


def stage(manifest_path: Path, into: Path) -> Path:
    """Copy the package and the manifest into ``into`` (the extension's root folder)."""
    root = into / PACKAGE_DIR.name
    shutil.copytree(PACKAGE_DIR, root, ignore=shutil.ignore_patterns(*EXCLUDE))
    shutil.copyfile(manifest_path, root / "blender_manifest.toml")
    return root


def _tool(tool: Path, *args) -> tuple[int, list[str]]:
    """Run blender_ext.py; its exit status and messages."""
    result = subprocess.run([sys.executable, str(tool), *args, "--output-type", "JSON"],
                            capture_output=True, text=True, timeout=600)
    messages = []
    for line in (result.stdout + "\n" + result.stderr).splitlines():
        line = line.strip()
        if not line:
            continue
        try:
            kind, text = json.loads(line)
            messages.append(str(text))
        except (ValueError, TypeError):
            messages.append(line)
    return result.returncode, messages


def validate(tool: Path, source: Path) -> None:
    code, messages = _tool(tool, "validate", str(source))
    if code != 0:
        problems = [m for m in messages if not m.startswith(("Success", "Error parsing TOML"))] or messages
        raise OptionError(f"extension validation failed: {'; '.join(problems) or f'exit status {code}'}")


def build(out_dir: Path, manifest_path: Path = MANIFEST, overwrite: bool = False) -> Path:
    """Validate and build the extension zip into ``out_dir``; its path."""
    manifest = read_manifest(manifest_path)
    zip_path = Path(out_dir) / f"{manifest['id']}-{manifest['version']}.zip"
    if zip_path.exists() and not overwrite:
        raise FileExistsError(f"{zip_path}: already exists (use --overwrite to replace it)")
    tool = blender_ext_tool()
    zip_path.parent.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory(prefix="blender-match-ext-") as tmp:
        source = stage(manifest_path, Path(tmp))
        validate(tool, source)
        # Build next to the destination, then rename: no half-written zip at the final name.
        with tempfile.TemporaryDirectory(prefix=".build-", dir=zip_path.parent) as build_dir:
            built = Path(build_dir) / zip_path.name
            code, messages = _tool(tool, "build", "--source-dir", str(source), "--output-filepath", str(built))
            if code != 0 or not built.is_file():
                raise OptionError(f"extension build failed: {'; '.join(messages) or f'exit status {code}'}")
            validate(tool, built)
            os.replace(built, zip_path)
    return zip_path


def check(manifest_path: Path = MANIFEST) -> dict:
    """Validate the staged extension without building; the manifest."""
    manifest = read_manifest(manifest_path)
    tool = blender_ext_tool()
    with tempfile.TemporaryDirectory(prefix="blender-match-ext-") as tmp:
        validate(tool, stage(manifest_path, Path(tmp)))
    return manifest


def run(args) -> int:
    if args.check:
        manifest = check(args.manifest)
        print(f"{manifest['id']} {manifest['version']}: valid extension")
        return 0
    if not args.out:
        raise OptionError("build-extension: give --out DIR (or --check)")
    print(build(args.out, args.manifest, args.overwrite))
    return 0
