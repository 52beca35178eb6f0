"""Others' selections in the viewport: a gpu draw handler that draws each
participant's selected vertices at their limit positions (presence,
docs/PROTOCOL.md section 6.3), one colour per participant."""

import bpy

from .connection import CONNECTION

COLOURS = [(0.2, 0.8, 1.0, 1.0), (1.0, 0.35, 0.2, 1.0), (0.6, 1.0, 0.3, 1.0), (1.0, 0.85, 0.2, 1.0)]
handle = [None]


def presence(context=None):
    """[(document, participant name, world points)] to draw."""
    out = []
    if not CONNECTION.connected:
        return out
    for doc in CONNECTION.documents.values():
        try:
            for name, points in doc.presence_points(CONNECTION.session, CONNECTION.tessera):
                out.append((doc, name, points))
        except Exception:
            continue  # drawing never raises; the poll reports the connection
    return out


def draw():
    import gpu
    from gpu_extras.batch import batch_for_shader

    shader = gpu.shader.from_builtin("3D_UNIFORM_COLOR")
    gpu.state.point_size_set(9.0)
    gpu.state.depth_test_set("NONE")
    for k, (_doc, _name, points) in enumerate(presence()):
        if len(points) == 0:
            continue
        batch = batch_for_shader(shader, "POINTS", {"pos": [tuple(p) for p in points]})
        shader.bind()
        shader.uniform_float("color", COLOURS[k % len(COLOURS)])
        batch.draw(shader)
    gpu.state.point_size_set(1.0)


def register():
    if not bpy.app.background:
        handle[0] = bpy.types.SpaceView3D.draw_handler_add(draw, (), "WINDOW", "POST_VIEW")


def unregister():
    if handle[0] is not None:
        bpy.types.SpaceView3D.draw_handler_remove(handle[0], "WINDOW")
        handle[0] = None
