"""Blender's side of run_ui_grab.py: a real Blender window (under Xvfb),
the add-on from its zip, a cube's document with its cage in Edit Mode and
vertex 0 selected. run_ui_grab.py then grabs with the mouse (G, moves, a
click) through xdotool; this script, on its timer as in a user's session,
checks that nothing reached the server while dragging and that the release
sent one edit batch that moved v0:0 on the server (read by a second, plain
session), and that Blender's own Ctrl+Z after it sends nothing and leaves
the cage as the server has it. Arguments after `--`: ROOT PORT TOKEN_FILE.
Exit code 0 on success."""

import os
import sys

import bmesh
import bpy
import numpy as np

ROOT, PORT, TOKEN_FILE = sys.argv[sys.argv.index("--") + 1:]
TOKEN = open(TOKEN_FILE).read().strip()
state = {"ticks": 0, "failure": None}


def marker(name):
    return os.path.exists(os.path.join(ROOT, name))


def write_marker(name):
    with open(os.path.join(ROOT, name), "w") as f:
        f.write("1")


def check(condition, message):
    if not condition:
        raise AssertionError(message)


def setup():
    bpy.ops.preferences.addon_enable(module="tessera_blender")
    from tessera_blender.connection import CONNECTION

    s = bpy.context.scene.tessera
    s.host, s.port, s.token = "127.0.0.1", int(PORT), TOKEN
    bpy.ops.tessera.connect()
    cube = bpy.data.objects["Cube"]
    bpy.context.view_layer.objects.active = cube
    cube.select_set(True)
    bpy.ops.tessera.create_from_mesh()
    doc = next(iter(CONNECTION.documents.values()))
    bpy.context.view_layer.objects.active = doc.cage_object
    doc.cage_object.select_set(True)
    bpy.ops.object.mode_set(mode="EDIT")
    bpy.ops.mesh.select_all(action="DESELECT")
    bm = bmesh.from_edit_mesh(doc.cage_object.data)
    bm.verts.ensure_lookup_table()
    bm.verts[0].select = True
    bmesh.update_edit_mesh(doc.cage_object.data)
    import tessera

    second = tessera.Session.connect("127.0.0.1", int(PORT), TOKEN, name="checker")
    second.open_document(doc.document_id)
    state.update(doc=doc, second=second, start=server_point(second, doc.document_id))


def server_point(second, document_id):
    from tessera_blender.glb_positions import glb_positions

    version, glb = second.export_document(document_id, 0)
    return version, glb_positions(glb)[0]


def start_point():
    return state["start"][1]


def step():
    state["ticks"] += 1
    try:
        if state["ticks"] == 1:
            setup()
            write_marker("ready")
        elif marker("dragging") and "during" not in state:
            state["during"] = server_point(state["second"], state["doc"].document_id)
            write_marker("checked-dragging")
        elif marker("released") and "released" not in state:
            start_version, start = state["start"]
            during_version, during = state["during"]
            check(during_version == start_version and np.allclose(during, start),
                  f"nothing is sent while dragging: version {start_version} -> {during_version}")
            version, after = server_point(state["second"], state["doc"].document_id)
            check(version == start_version + 1, f"the release sent one batch: {start_version} -> {version}")
            check(np.linalg.norm(after - start) > 1e-3, f"v0:0 moved on the server: {start} -> {after}")
            state["released"] = (version, after)
            write_marker("checked-released")
        elif marker("undone") and "released" in state:
            # Blender's Ctrl+Z: the cage shows the server's state again and
            # nothing is sent (docs/BLENDER.md, "Undo").
            version, after = state["released"]
            now_version, now = server_point(state["second"], state["doc"].document_id)
            check(now_version == version and np.allclose(now, after),
                  f"Blender's undo sent nothing: version {version} -> {now_version}")
            # The undo may land in Edit Mode or, this script having entered
            # it without an undo step of its own, in Object Mode.
            cage = state["doc"].cage_object
            if cage.mode == "EDIT":
                bm = bmesh.from_edit_mesh(cage.data)
                bm.verts.ensure_lookup_table()
                shown = np.array(bm.verts[0].co[:])
            else:
                shown = np.array(cage.data.vertices[0].co[:])
            check(np.abs(shown - after).max() < 1e-5,
                  f"after Blender's undo the cage shows the server's v0:0 {after}, not {shown}")
            print(f"PASSED ui_grab_release: v0:0 {start_point()} -> {after}, version {version}")
            return finish(0)
        elif state["ticks"] > 150:
            raise AssertionError("the mouse never released the grab")
    except Exception:
        import traceback

        traceback.print_exc()
        return finish(1)
    return 0.1


def finish(code):
    sys.stdout.flush()
    os._exit(code)


bpy.app.timers.register(step, first_interval=0.5)
