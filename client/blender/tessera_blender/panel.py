"""The sidebar panel (3D Viewport > N > Tessera)."""

import bpy

from .connection import CONNECTION
from .operators import active_document


class TESSERA_PT_panel(bpy.types.Panel):
    bl_label = "Tessera"
    bl_idname = "TESSERA_PT_panel"
    bl_space_type = "VIEW_3D"
    bl_region_type = "UI"
    bl_category = "Tessera"

    def draw(self, context):
        s = context.scene.tessera
        layout = self.layout
        box = layout.box()
        box.label(text=CONNECTION.message, icon="ERROR" if CONNECTION.error else "INFO")
        col = layout.column(align=True)
        col.prop(s, "host")
        col.prop(s, "port")
        col.prop(s, "token")
        col.prop(s, "client_name")
        row = layout.row(align=True)
        row.operator("tessera.connect")
        row.operator("tessera.disconnect")
        if not CONNECTION.connected and not CONNECTION.lost:
            return
        layout.separator()
        row = layout.row(align=True)
        row.prop(s, "document", text="")
        row.operator("tessera.list_documents", text="", icon="FILE_REFRESH")
        layout.operator("tessera.open_document")
        layout.prop(s, "max_level")
        layout.operator("tessera.create_from_mesh")
        layout.separator()
        row = layout.row(align=True)
        row.prop(s, "lod")
        row.prop(s, "edit_level")
        layout.operator("tessera.apply_lod")
        doc = active_document(context)
        if doc is None:
            return
        scheme = f", {doc.scheme}" if doc.scheme else ""
        layout.label(text=f"{doc.name} ({doc.document_id}{scheme}) at version {doc.limit_version}")
        layout.operator("tessera.send_edits")
        row = layout.row(align=True)
        row.operator("tessera.undo", text=f"Undo ({len(doc.undo_stack)})", icon="LOOP_BACK")
        row.operator("tessera.redo", text=f"Redo ({len(doc.redo_stack)})", icon="LOOP_FORWARDS")
        layout.label(text="Participants:")
        if CONNECTION.connected:
            for p in CONNECTION.session.participants(doc.document_id):
                me = " (you)" if p.session_id == CONNECTION.session.session_id else ""
                layout.label(text=f"  {p.name}{me}: {p.role}, {len(p.selected_vertex_ids)} selected",
                             icon="USER")


def register():
    bpy.utils.register_class(TESSERA_PT_panel)


def unregister():
    bpy.utils.unregister_class(TESSERA_PT_panel)
