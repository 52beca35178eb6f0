"""Tessera for Blender: live, collaborative subdivision documents in the viewport.

The add-on is a thin layer over the `tessera` Python package
(docs/PYTHON.md): every message it sends is built by the package, which
wraps the C++ client library; nothing here speaks the protocol itself.
docs/BLENDER.md describes the panel, the edits and how undo works.
"""

bl_info = {
    "name": "Tessera",
    "author": "Tessera contributors",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "3D Viewport > Sidebar > Tessera",
    "description": "Edit tessera-server documents live: control cage, limit surface, presence",
    "doc_url": "https://example.invalid/tessera/docs/BLENDER.md",
    "category": "3D View",
}

from . import handlers, operators, panel, presence_draw, properties  # noqa: E402


def register():
    properties.register()
    operators.register()
    panel.register()
    handlers.register()
    presence_draw.register()


def unregister():
    presence_draw.unregister()
    handlers.unregister()
    panel.unregister()
    operators.unregister()
    properties.unregister()
