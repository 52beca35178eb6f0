"""Takes docs/images/blender-live-document.png: Blender's window with a live
document, the Tessera panel open, a second participant's selection drawn.

Run by make_screenshot.sh under Xvfb (Mesa's software OpenGL), with the
add-on installed from its zip and an empty .blend (a file on the command
line keeps the splash screen away); a second, plain `tessera` session,
"alice", plays the collaborator: she made the document, edited it
(deploy/samples/session_quads.txt) and selected the top face's corners. Arguments after `--`: PORT TOKEN_FILE SAMPLES_DIR OUT.
"""

import os
import sys

import bpy

PORT, TOKEN_FILE, SAMPLES, OUT = sys.argv[sys.argv.index("--") + 1:]
TOKEN = open(TOKEN_FILE).read().strip()
state = {"ticks": 0}


def setup():
    bpy.ops.preferences.addon_enable(module="tessera_blender")
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj)
    s = bpy.context.scene.tessera
    s.host, s.port, s.token, s.client_name = "127.0.0.1", int(PORT), TOKEN, "blender"
    bpy.ops.tessera.connect()
    import tessera

    other = tessera.Session.connect("127.0.0.1", int(PORT), TOKEN, name="alice")
    ack = other.create_document(os.path.join(SAMPLES, "quad_cube.obj"), name="quad cube",
                                tags=os.path.join(SAMPLES, "cube.tags"), max_level=4)
    other.open_document(ack.document_id)
    with open(os.path.join(SAMPLES, "session_quads.txt")) as f:
        other.edit(ack.document_id, f.read())
    other.select(ack.document_id, ["v0:0", "v0:1", "v0:2", "v0:3"])
    state["other"] = other
    bpy.ops.tessera.list_documents()
    s.document = str(ack.document_id)
    s.lod, s.edit_level = 3, 3
    bpy.ops.tessera.open_document()
    from tessera_blender.connection import CONNECTION

    doc = next(iter(CONNECTION.documents.values()))
    bpy.context.view_layer.objects.active = doc.cage_object
    doc.cage_object.select_set(True)
    for area in bpy.context.screen.areas:
        if area.type == "VIEW_3D":
            space = area.spaces[0]
            space.show_region_ui = True
            space.shading.type = "SOLID"
            space.shading.light = "MATCAP"
            space.overlay.show_floor = False
            space.overlay.show_axis_x = False
            space.overlay.show_axis_y = False
            region = space.region_3d
            region.view_perspective = "PERSP"
            region.view_rotation = (0.78, 0.48, 0.2, 0.35)
            region.view_location = tuple(doc.known_points.mean(axis=0))
            region.view_distance = 3.0


def show_panel_first():
    """The sidebar opens on its first tab, and Blender 3.4 has no call to
    pick another: for this picture the Tessera panel is registered under
    the first tab's name."""
    from tessera_blender import panel

    bpy.utils.unregister_class(panel.TESSERA_PT_panel)
    panel.TESSERA_PT_panel.bl_category = "Item"
    bpy.utils.register_class(panel.TESSERA_PT_panel)
    bpy.utils.unregister_class(bpy.types.VIEW3D_PT_context_properties)
    # The tab's Transform panel is Blender's own (C), it stays: a smaller UI
    # makes room for the Tessera panel under it.
    bpy.context.preferences.view.ui_scale = 0.8


def shoot():
    state["ticks"] += 1
    if state["ticks"] == 1:
        setup()
        show_panel_first()
        return 0.5
    if state["ticks"] < 6:
        for area in bpy.context.screen.areas:
            area.tag_redraw()
        return 0.5
    bpy.ops.screen.screenshot(filepath=OUT)
    state["other"].close()
    bpy.ops.wm.quit_blender()
    return None


bpy.app.timers.register(shoot, first_interval=1.0)
