"""The add-on registers with Blender (the real bpy module) without importing torch."""
from __future__ import annotations

import subprocess
import sys
import textwrap

from conftest import ROOT

SCRIPT = textwrap.dedent("""
    import sys
    import bpy
    import blender_match
    blender_match.register()
    assert "torch" not in sys.modules, "registering the add-on imported torch"
    blender_match.unregister()
    assert "torch" not in sys.modules
    print("REGISTERED-OK")
""")


def test_register_and_unregister_without_torch():
    result = subprocess.run([sys.executable, "-c", SCRIPT], cwd=ROOT, capture_output=True, text=True, timeout=300)
    assert result.returncode == 0, result.stderr[-2000:]
    assert "REGISTERED-OK" in result.stdout


def test_cli_package_imports_without_bpy_or_torch():
    code = "import sys, blender_match; assert 'bpy' not in sys.modules and 'torch' not in sys.modules"
    result = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, timeout=120)
    assert result.returncode == 0, result.stderr[-2000:]
