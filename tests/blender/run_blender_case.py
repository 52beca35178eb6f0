"""Runs one case of addon_cases.py in Blender, headless, for ctest.

`python3 run_blender_case.py CASE`: exits 77 (ctest's SKIP_RETURN_CODE
for these tests) when no Blender is installed; otherwise makes a temporary
root (the server's data, Blender's user scripts folder where the add-on's
zip is installed, exports), runs
`blender -b --factory-startup --python addon_cases.py -- CASE ROOT` bounded
by CASE_SECONDS, and removes the root whatever happened (TESSERA_KEEP_TEST_DIRS=1
keeps it). Environment (set by tests/blender/CMakeLists.txt):
TESSERA_SERVER, TESSERA_CLI, TESSERA_BLENDER_ZIP, and for install_rules TESSERA_BUILD_DIR
and CMAKE_COMMAND.
"""

import os
import shutil
import subprocess
import sys
import tempfile

CASE_SECONDS = 14
SKIP = 77


def main():
    case = sys.argv[1]
    blender = os.environ.get("TESSERA_BLENDER") or shutil.which("blender")
    if not blender:
        print("blender is not installed: skipped (deploy/install-deps.sh installs it)")
        return SKIP
    root = tempfile.mkdtemp(prefix=f"tessera-blender-{case}-")
    here = os.path.dirname(os.path.abspath(__file__))
    env = dict(os.environ)
    env["BLENDER_USER_SCRIPTS"] = os.path.join(root, "scripts")
    env["BLENDER_USER_CONFIG"] = os.path.join(root, "config")
    env["TMPDIR"] = root
    env["PYTHONDONTWRITEBYTECODE"] = "1"
    try:
        if case == "install_rules":
            # The add-on's install rules into a prefix of the test's own, and
            # Blender told to read that prefix's scripts folder (Debian's
            # Blender has its system folder built in, /usr/share/blender/scripts).
            prefix = os.path.join(root, "prefix")
            subprocess.run([os.environ.get("CMAKE_COMMAND", "cmake"), "--install",
                            os.environ["TESSERA_BUILD_DIR"], "--component", "tessera_blender",
                            "--prefix", prefix], check=True, timeout=CASE_SECONDS)
            env["BLENDER_USER_SCRIPTS"] = os.path.join(prefix, "share", "blender", "scripts")
        result = subprocess.run(
            [blender, "-b", "--factory-startup", "--python-exit-code", "1",
             "--python", os.path.join(here, "addon_cases.py"), "--", case, root],
            env=env, timeout=CASE_SECONDS)
        return result.returncode
    except subprocess.TimeoutExpired:
        print(f"{case}: Blender did not finish within {CASE_SECONDS} s")
        return 1
    finally:
        if os.environ.get("TESSERA_KEEP_TEST_DIRS") == "1":
            print(f"kept {root}")
        else:
            shutil.rmtree(root, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
