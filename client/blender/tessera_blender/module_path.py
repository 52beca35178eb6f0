"""Finding the `tessera` Python package from inside Blender.

Debian's Blender runs Debian's python3, so a package installed by
`cmake --install` (into /usr/lib/python3/dist-packages, docs/PYTHON.md
"Build and install") is importable as it is. A build tree's package is
not on Blender's path, and Blender ignores PYTHONPATH unless started with
--python-use-system-env; so the add-on also tries, in this order:
the folder in the environment variable TESSERA_PYTHONPATH, the folder set
in the add-on's preferences, and the folders CMake wrote into
configured_paths.py when it built the add-on (the install folder, then
the build tree's).
"""

import importlib
import os
import sys

try:
    from .configured_paths import CONFIGURED_DIRS
except ImportError:  # running from the source tree, not configured by CMake
    CONFIGURED_DIRS = []


def candidate_dirs(preference_dir=""):
    """The folders that may hold a `tessera/` package, first to try first."""
    dirs = []
    env = os.environ.get("TESSERA_PYTHONPATH", "")
    dirs += [d for d in env.split(os.pathsep) if d]
    if preference_dir:
        dirs.append(bpy_abspath(preference_dir))
    dirs += [d for d in CONFIGURED_DIRS if d]
    return dirs


def bpy_abspath(path):
    try:
        import bpy

        return bpy.path.abspath(path)
    except ImportError:
        return path


def import_tessera(preference_dir=""):
    """Returns the `tessera` module, adding the first folder that holds it to
    sys.path when it is not importable already. Raises ImportError naming
    every folder tried."""
    try:
        return importlib.import_module("tessera")
    except ImportError:
        pass
    tried = []
    for folder in candidate_dirs(preference_dir):
        tried.append(folder)
        if os.path.isfile(os.path.join(folder, "tessera", "__init__.py")):
            if folder not in sys.path:
                sys.path.insert(0, folder)
            return importlib.import_module("tessera")
    raise ImportError(
        "the tessera Python package is not installed for Blender's Python "
        f"({sys.version.split()[0]}); tried sys.path and {tried or 'no other folder'}. "
        "Build it (cmake --build build/release --target _tessera), install it "
        "(cmake --install), or set its folder in the add-on's preferences")
