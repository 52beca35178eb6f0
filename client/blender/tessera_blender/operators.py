"""The panel's buttons. Each reports a failure with its reason
(self.report) and leaves it on the panel's message line."""

import os
import tempfile

import bpy

from . import base_mesh, properties
from .connection import CONNECTION


def module_dir(context):
    prefs = properties.preferences(context)
    return prefs.module_dir if prefs else ""


def active_document(context):
    """The LiveDocument of the active object (its cage or limit object)."""
    obj = context.active_object
    if obj is not None and "tessera_document_id" in obj:
        doc = CONNECTION.documents.get(int(obj["tessera_document_id"]))
        if doc is not None:
            return doc
    if len(CONNECTION.documents) == 1:
        return next(iter(CONNECTION.documents.values()))
    return None


class TesseraOperator(bpy.types.Operator):
    """Runs `act`, turning any failure into an error report."""

    def execute(self, context):
        try:
            message = self.act(context)
        except Exception as e:  # every failure is shown, named, in the UI
            text = str(e) or type(e).__name__
            if not CONNECTION.error or CONNECTION.message != text:
                CONNECTION.set_error(text)
            self.report({"ERROR"}, text)
            return {"CANCELLED"}
        if message:
            self.report({"INFO"}, message)
        return {"FINISHED"}


class TESSERA_OT_connect(TesseraOperator):
    bl_idname = "tessera.connect"
    bl_label = "Connect"
    bl_description = "Connect to the tessera-server with the token"

    def act(self, context):
        s = context.scene.tessera
        if not s.token:
            raise ValueError("no token: paste the server's access token into the panel")
        CONNECTION.connect(s.host, s.port, s.token, s.client_name, module_dir(context))
        CONNECTION.list_documents()
        return CONNECTION.message


class TESSERA_OT_disconnect(TesseraOperator):
    bl_idname = "tessera.disconnect"
    bl_label = "Disconnect"

    def act(self, context):
        CONNECTION.disconnect()
        return "Disconnected"


class TESSERA_OT_list(TesseraOperator):
    bl_idname = "tessera.list_documents"
    bl_label = "List documents"

    def act(self, context):
        docs = CONNECTION.run(lambda session: CONNECTION.list_documents())
        return f"{len(docs)} document(s)"


class TESSERA_OT_open(TesseraOperator):
    bl_idname = "tessera.open_document"
    bl_label = "Open"
    # An undo step once the objects exist: Blender's undo must not go back
    # past their creation to a state without them (docs/BLENDER.md "Undo").
    bl_options = {"REGISTER", "UNDO"}
    bl_description = "Open the chosen document as a control cage and a live limit surface"

    document_id: bpy.props.IntProperty(name="Document", default=0)

    def act(self, context):
        s = context.scene.tessera
        document_id = self.document_id or int(s.document or 0)
        if document_id <= 0:
            raise ValueError("no document chosen: list the server's documents and pick one")
        names = {d.document_id: d.name for d in CONNECTION.listed}
        doc = CONNECTION.run(lambda session: CONNECTION.open_document(
            document_id, names.get(document_id, f"document {document_id}"), s.lod, s.edit_level))
        return f"Opened document {doc.document_id} ({doc.name})"


class TESSERA_OT_create(TesseraOperator):
    bl_idname = "tessera.create_from_mesh"
    bl_label = "Create from active mesh"
    bl_options = {"REGISTER", "UNDO"}  # as Open's
    bl_description = ("Create a document from the active mesh, its edge and vertex creases as "
                      "tags, the scheme from its Subdivision Surface modifier")

    def act(self, context):
        s = context.scene.tessera
        obj = context.active_object
        mesh = base_mesh.read_base_mesh(obj)
        scheme, why = base_mesh.choose_scheme(obj, mesh)
        doc = create_document(obj, mesh, scheme, s.max_level, min(s.lod, s.max_level),
                              min(s.edit_level, s.max_level))
        obj.hide_set(True)
        return f"Created document {doc.document_id} '{doc.name}' ({scheme}: {why})"


def create_document(obj, mesh, scheme, max_level, lod, edit_level):
    """Sends the mesh, opens the document, makes its two objects."""
    tags_text = base_mesh.tag_file_text(mesh)
    tags_path = None
    try:
        if tags_text:
            fd, tags_path = tempfile.mkstemp(prefix="tessera-blender-", suffix=".tags")
            with os.fdopen(fd, "w") as f:
                f.write(tags_text)
        faces = mesh.faces
        ack = CONNECTION.run(lambda session: session.create_document_from_arrays(
            mesh.points, faces, name=obj.name, tags=tags_path, max_level=max_level, scheme=scheme))
    finally:
        if tags_path:
            os.unlink(tags_path)
    CONNECTION.run(lambda session: CONNECTION.list_documents())
    from .live_document import LiveDocument

    doc = LiveDocument(ack.document_id, obj.name, ack.scheme, lod, edit_level)
    doc.known_edge_creases = dict(mesh.edge_creases)
    doc.known_vertex_creases = dict(mesh.vertex_creases)
    CONNECTION.run(lambda session: doc.attach(session, CONNECTION.tessera))
    doc.make_objects(obj.matrix_world.copy())
    CONNECTION.documents[doc.document_id] = doc
    CONNECTION.poll()
    return doc


class TESSERA_OT_send(TesseraOperator):
    bl_idname = "tessera.send_edits"
    bl_label = "Send cage edits"
    bl_description = "Send the moved cage vertices, changed creases and moved limit points now"

    def act(self, context):
        doc = require(context)
        ack = CONNECTION.run(lambda session: doc.send_changes(session, CONNECTION.tessera))
        return f"Sent as version {ack.version}" if ack else "Nothing changed"


def require(context):
    doc = active_document(context)
    if doc is None:
        raise ValueError("select a Tessera cage or limit object (or open a document)")
    return doc


class TESSERA_OT_undo(TesseraOperator):
    bl_idname = "tessera.undo"
    bl_label = "Tessera undo"
    bl_description = "Undo your last edit batch on the server (others' edits stay)"

    def act(self, context):
        doc = require(context)
        CONNECTION.run(lambda session: doc.undo(session))
        CONNECTION.poll()
        return "Undone on the server"


class TESSERA_OT_redo(TesseraOperator):
    bl_idname = "tessera.redo"
    bl_label = "Tessera redo"
    bl_description = "Redo your last undone edit batch on the server"

    def act(self, context):
        doc = require(context)
        CONNECTION.run(lambda session: doc.redo(session))
        CONNECTION.poll()
        return "Redone on the server"


class TESSERA_OT_set_lod(TesseraOperator):
    bl_idname = "tessera.apply_lod"
    bl_label = "Apply LOD"
    bl_description = "Show the limit surface at the panel's LOD, edit limit points at its edit level"

    def act(self, context):
        doc = require(context)
        s = context.scene.tessera
        doc.edit_level = s.edit_level
        CONNECTION.run(lambda session: doc.resubscribe(session, s.lod))
        CONNECTION.poll()
        return f"Limit surface at level {s.lod}"


classes = (TESSERA_OT_connect, TESSERA_OT_disconnect, TESSERA_OT_list, TESSERA_OT_open,
           TESSERA_OT_create, TESSERA_OT_send, TESSERA_OT_undo, TESSERA_OT_redo, TESSERA_OT_set_lod)
keymaps = []


def register():
    for c in classes:
        bpy.utils.register_class(c)
    # Ctrl+Alt+Z / Ctrl+Alt+Shift+Z: Tessera's undo and redo beside Blender's own.
    config = bpy.context.window_manager.keyconfigs.addon
    if config is not None:
        km = config.keymaps.new(name="3D View", space_type="VIEW_3D")
        keymaps.append((km, km.keymap_items.new(TESSERA_OT_undo.bl_idname, "Z", "PRESS", ctrl=True, alt=True)))
        keymaps.append((km, km.keymap_items.new(TESSERA_OT_redo.bl_idname, "Z", "PRESS", ctrl=True, alt=True,
                                                shift=True)))


def unregister():
    for km, item in keymaps:
        km.keymap_items.remove(item)
    keymaps.clear()
    for c in reversed(classes):
        bpy.utils.unregister_class(c)
