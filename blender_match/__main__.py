"""``python -m blender_match``: the blender-match command."""
import sys

from .cli import main

sys.exit(main())
