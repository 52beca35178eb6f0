"""A grab released with the mouse in a real Blender window sends the cage
edit: Debian's Blender under Xvfb (Mesa's software OpenGL), driven by
xdotool (G, two moves, a click, then Ctrl+Z), against a real tessera-server
(server_process.py) on a temporary store; ui_grab_case.py checks the
server from inside Blender. Exits 77 (skipped) when blender, xvfb-run or
xdotool is missing; removes its temporary folder."""

import os
import shutil
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from server_process import Server  # noqa: E402

SECONDS = 12
SKIP = 77


def wait_for(path, seconds):
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline:
        if os.path.exists(path):
            return True
        time.sleep(0.05)
    return False


def main():
    tools = {name: shutil.which(name) for name in ("blender", "xvfb-run", "xdotool")}
    missing = [name for name, path in tools.items() if not path]
    if missing:
        print(f"{', '.join(missing)} not installed: skipped (deploy/install-deps.sh installs them)")
        return SKIP
    root = tempfile.mkdtemp(prefix="tessera-blender-ui-grab-")
    server = None
    try:
        server = Server(os.environ["TESSERA_SERVER"], root)
        env = dict(os.environ, TMPDIR=root, PYTHONDONTWRITEBYTECODE="1",
                   BLENDER_USER_SCRIPTS=os.path.join(root, "scripts"),
                   BLENDER_USER_CONFIG=os.path.join(root, "config"))
        addons = os.path.join(root, "scripts", "addons")
        os.makedirs(addons)
        subprocess.run(["cmake", "-E", "tar", "xf", os.environ["TESSERA_BLENDER_ZIP"]], cwd=addons, check=True)
        # A file on the command line keeps the splash screen, which would take the click, away.
        empty = os.path.join(root, "empty.blend")
        subprocess.run(["blender", "-b", "--factory-startup", "--python-expr",
                        f"import bpy; bpy.ops.wm.save_as_mainfile(filepath={empty!r})"],
                       env=env, check=True, timeout=SECONDS, stdout=subprocess.DEVNULL)
        script = os.path.join(root, "drive.sh")
        with open(script, "w") as f:
            f.write(DRIVE)
        result = subprocess.run(
            ["xvfb-run", "-a", "-s", "-screen 0 1024x700x24", "bash", script, root, str(server.port),
             server.token_file, empty, os.path.join(HERE, "ui_grab_case.py")],
            env=env, timeout=SECONDS + 12)
        return result.returncode
    except subprocess.TimeoutExpired:
        print(f"ui_grab_release: not finished in time ({SECONDS} s per Blender run, {SECONDS + 12} s under Xvfb)")
        return 1
    finally:
        if server is not None:
            server.stop()
        if os.environ.get("TESSERA_KEEP_TEST_DIRS") == "1":
            print(f"kept {root}")
        else:
            shutil.rmtree(root, ignore_errors=True)


# Inside the X server: Blender, then the user's hand. G starts a grab of the
# selected vertex, the moves drag it, the click releases it; then Ctrl+Z,
# Blender's own undo.
DRIVE = r"""
set -u
root=$1 port=$2 token=$3 empty=$4 case=$5
blender --factory-startup --window-geometry 0 0 1024 700 "$empty" \
  --python "$case" -- "$root" "$port" "$token" &
blender_pid=$!
for _ in $(seq 200); do [ -f "$root/ready" ] && break; sleep 0.1; done
sleep 0.5
window=$(xdotool search --name Blender | head -1)
xdotool windowfocus "$window"
xdotool mousemove 400 300; sleep 0.3
xdotool key g; sleep 0.3
xdotool mousemove 420 250; sleep 0.3
xdotool mousemove 440 200; sleep 0.3
touch "$root/dragging"
for _ in $(seq 100); do [ -f "$root/checked-dragging" ] && break; sleep 0.1; done
xdotool click 1; sleep 0.5
touch "$root/released"
for _ in $(seq 100); do [ -f "$root/checked-released" ] && break; sleep 0.1; done
xdotool key ctrl+z; sleep 0.5
touch "$root/undone"
wait $blender_pid
"""

if __name__ == "__main__":
    sys.exit(main())
