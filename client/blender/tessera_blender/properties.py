"""The panel's settings (scene properties) and the add-on's preferences."""

import bpy


class TesseraPreferences(bpy.types.AddonPreferences):
    bl_idname = __package__

    module_dir: bpy.props.StringProperty(
        name="tessera package folder",
        description="Folder that holds the tessera/ Python package, when Blender's Python "
                    "does not find it (build/release/client/python in a build tree)",
        subtype="DIR_PATH")

    def draw(self, context):
        self.layout.prop(self, "module_dir")


# Blender keeps only pointers to a dynamic enum's strings: Python must keep
# the items alive, or the menu shows freed memory.
document_items_cache = []


def document_items(self, context):
    from .connection import CONNECTION

    items = [(str(d.document_id), f"{d.document_id}: {d.name}", f"version {d.version}")
             for d in CONNECTION.listed]
    document_items_cache[:] = items or [("0", "(list the server's documents)", "")]
    return document_items_cache


class TesseraSettings(bpy.types.PropertyGroup):
    host: bpy.props.StringProperty(name="Host", default="127.0.0.1")
    port: bpy.props.IntProperty(name="Port", default=7878, min=1, max=65535)
    token: bpy.props.StringProperty(name="Token", subtype="PASSWORD",
                                    description="An access token of the server (16 bytes or more)")
    client_name: bpy.props.StringProperty(name="Name", default="blender",
                                          description="How the others see you")
    document: bpy.props.EnumProperty(name="Document", items=document_items)
    max_level: bpy.props.IntProperty(name="Max level", default=4, min=1, max=8,
                                     description="Finest level of a new document")
    lod: bpy.props.IntProperty(name="Limit LOD", default=2, min=0, max=8,
                               description="Level of the limit surface shown")
    edit_level: bpy.props.IntProperty(name="Edit level", default=2, min=0, max=8,
                                      description="Level of the control points a moved limit point edits")


classes = (TesseraPreferences, TesseraSettings)


def preferences(context):
    addon = context.preferences.addons.get(__package__)
    return addon.preferences if addon else None


def register():
    for c in classes:
        bpy.utils.register_class(c)
    bpy.types.Scene.tessera = bpy.props.PointerProperty(type=TesseraSettings)


def unregister():
    del bpy.types.Scene.tessera
    for c in reversed(classes):
        bpy.utils.unregister_class(c)
