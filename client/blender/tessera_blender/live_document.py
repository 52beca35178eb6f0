"""One opened document: its cage and limit objects, and the edits between
them and the server.

- The cage (level 0's control points and polygons) is read from the
  server with `cage()` for the polygons and `export_document(doc, 0)` for
  the points, and rewritten whenever the stream shows a version this
  Blender did not make itself.
- The limit surface is the subscription's regions (`subscribe(doc,
  base_level=lod, max_level=lod)`), rewritten at each new version.
- `send_changes()` diffs the cage against the last cage known to be the
  server's, and sends every moved vertex (an offset, `offset v0:i by d`)
  and every changed crease (`crease e0:k S`) as one edit batch
  (docs/PROTOCOL.md section 13.1); it diffs the limit object against the
  last surface written and sends a direct manipulation of each moved limit
  point at the level chosen in the panel (`move vL:i to X Y Z`).
- Undo and redo are Tessera's, by edit id, of this Blender's own batches.
"""

import numpy as np

from . import creases, glb_positions, mesh_objects
from .edge_numbering import edge_numbers

# A vertex is moved when it is farther than this from where the server has
# it; Blender stores float32, so smaller differences are rounding.
MOVE_EPSILON = 1e-6


class TopologyChanged(ValueError):
    """The cage's vertices or faces are not the document's any more."""


class Batch:
    """One edit batch of this Blender: its edit ids, and the creases it set,
    before and after, so undo and redo can show them again."""

    def __init__(self, edit_ids, crease_changes):
        self.edit_ids = list(edit_ids)
        self.crease_changes = crease_changes  # (a, b) -> (before, after)


class LiveDocument:
    def __init__(self, document_id, name, scheme="", lod=2, edit_level=2):
        self.document_id = int(document_id)
        self.name = name
        self.scheme = scheme
        self.lod = lod
        self.edit_level = edit_level
        self.object_names = {}  # role ("cage", "limit") -> the object's name
        self.faces = []
        self.vertex_count = 0
        self.edges = {}
        self.known_points = np.zeros((0, 3))
        self.known_edge_creases = {}
        self.known_vertex_creases = {}
        self.cage_version = 0
        self.limit_version = 0
        self.limit_points = np.zeros((0, 3))
        self.limit_ids = np.zeros(0, dtype=np.uint64)
        self.undo_stack = []
        self.redo_stack = []
        self.last_selection = None

    # --- the two objects ----------------------------------------------------------
    # Held by name, never as bpy references: Blender's undo reloads its data,
    # and every reference taken before it is dead afterwards. A renamed
    # object is found again by its tessera_document_id and tessera_role.

    @property
    def cage_object(self):
        return self.find_object("cage")

    @cage_object.setter
    def cage_object(self, obj):
        self.keep_object("cage", obj)

    @property
    def limit_object(self):
        return self.find_object("limit")

    @limit_object.setter
    def limit_object(self, obj):
        self.keep_object("limit", obj)

    def keep_object(self, role, obj):
        obj["tessera_document_id"] = self.document_id
        obj["tessera_role"] = role
        self.object_names[role] = obj.name

    def find_object(self, role):
        import bpy

        name = self.object_names.get(role)
        if name is None:
            return None
        obj = bpy.data.objects.get(name)
        if obj is not None and obj.get("tessera_role") == role:
            return obj
        for obj in bpy.data.objects:
            if obj.get("tessera_document_id") == self.document_id and obj.get("tessera_role") == role:
                self.object_names[role] = obj.name
                return obj
        return None

    # --- attaching to a session -------------------------------------------------

    def attach(self, session, tessera):
        """Opens the document and subscribes at the panel's LOD; rereads the
        cage (after a reconnection too: edits may have happened meanwhile)."""
        session.open_document(self.document_id)
        session.subscribe(self.document_id, base_level=self.lod, max_level=self.lod)
        _, sizes, corners = session.cage(self.document_id, 0)
        faces, at = [], 0
        for size in sizes.tolist():
            faces.append([int(c) for c in corners[at:at + size]])
            at += size
        self.faces = faces
        self.vertex_count = int(corners.max()) + 1 if len(corners) else 0
        self.edges = edge_numbers(faces)
        self.refresh_cage(session)

    def resubscribe(self, session, lod):
        """Another LOD for the limit surface (the panel's)."""
        self.lod = lod
        session.unsubscribe(self.document_id)
        session.subscribe(self.document_id, base_level=lod, max_level=lod)
        self.limit_version = 0

    def refresh_cage(self, session):
        """Rereads the level-0 control points and writes them into the cage,
        unless the user has moved cage vertices not yet sent."""
        version, glb = session.export_document(self.document_id, 0)
        # The GLB's first vertices are the level's, in order; vertices split
        # along sharp features for their normals follow them.
        points = glb_positions.glb_positions(glb)[:self.vertex_count]
        if self.cage_object is not None and self.cage_has_pending_moves():
            return
        self.known_points = points
        self.cage_version = version
        if self.cage_object is not None:
            if len(self.cage_object.data.vertices) != len(points) and self.cage_object.mode != "EDIT":
                mesh_objects.write_polygons(self.cage_object.data, points, self.faces)
                self.write_known_creases()
            else:
                mesh_objects.write_cage_points(self.cage_object, points)

    def make_objects(self, matrix=None):
        """Creates the cage and the limit objects (once)."""
        if self.cage_object is None:
            cage = mesh_objects.new_object(f"{self.name} cage", f"{self.name} cage", matrix=matrix)
            mesh_objects.write_polygons(cage.data, self.known_points, self.faces)
            cage.display_type = "WIRE"
            cage.show_in_front = True
            self.cage_object = cage
            self.write_known_creases()
        if self.limit_object is None:
            self.limit_object = mesh_objects.new_object(
                f"{self.name} limit", f"{self.name} limit", matrix=matrix)

    def write_known_creases(self):
        mesh_objects.write_cage_creases(self.cage_object, self.known_edge_creases,
                                        self.known_vertex_creases)

    # --- the stream -----------------------------------------------------------

    def apply_view(self, session, tessera):
        """Rewrites the limit object when the session's view of the document
        shows a new version; rereads the cage when that version was not made
        here. Returns True when something changed."""
        if self.cage_object is None or self.limit_object is None:
            # Deleted, or undone by Blender's undo: the document is still open.
            self.make_objects()
            self.limit_version = 0
        view = session.view(self.document_id)
        if view is None or not view.ready or view.version == self.limit_version:
            return False
        ids = view.vertex_ids()
        points = view.positions()
        triangles = view.triangles()
        unique, first, inverse = np.unique(ids, return_index=True, return_inverse=True)
        self.limit_ids = unique
        self.limit_points = points[first]
        faces = inverse[triangles]
        levels = np.array([tessera.id_level(int(i)) for i in unique], dtype=np.int32)
        indices = np.array([tessera.id_index(int(i)) for i in unique], dtype=np.int64)
        if self.limit_object is not None:
            mesh_objects.write_limit_surface(self.limit_object, self.limit_points, faces, levels, indices)
        self.limit_version = view.version
        if view.version > self.cage_version:
            self.refresh_cage(session)
        return True

    # --- edits ------------------------------------------------------------------

    def cage_has_pending_moves(self):
        points = mesh_objects.read_points(self.cage_object)
        if points.shape != self.known_points.shape:
            return False
        return bool(np.any(np.abs(points - self.known_points) > MOVE_EPSILON))

    def cage_script(self):
        """(edit script lines, crease changes) for what the user changed on
        the cage since the last known server state."""
        points = mesh_objects.read_points(self.cage_object)
        if points.shape != self.known_points.shape:
            raise TopologyChanged(
                f"the cage '{self.cage_object.name}' has {len(points)} vertices, the document "
                f"{len(self.known_points)}: Tessera edits move points and set creases, they never "
                "add or delete vertices; the cage is reset to the server's")
        lines = []
        moved = np.nonzero(np.any(np.abs(points - self.known_points) > MOVE_EPSILON, axis=1))[0]
        # Vertices moved by one displacement (a grab) share one offset line.
        groups = {}
        for i in moved.tolist():
            d = tuple(np.round(points[i] - self.known_points[i], 9).tolist())
            groups.setdefault(d, []).append(i)
        for d, vertices in groups.items():
            ids = " ".join(f"v0:{i}" for i in vertices)
            lines.append(f"offset {ids} by {d[0]!r} {d[1]!r} {d[2]!r}")
        edge_creases, vertex_creases = mesh_objects.read_creases(self.cage_object)
        crease_changes = {}
        for key in set(edge_creases) | set(self.known_edge_creases):
            before = self.known_edge_creases.get(key, 0.0)
            after = edge_creases.get(key, 0.0)
            if abs(before - after) > 1e-4:
                if key not in self.edges:
                    raise TopologyChanged(f"edge {key} is not an edge of the document")
                crease_changes[key] = (before, after)
                lines.append(f"crease e0:{self.edges[key]} "
                             f"{creases.sharpness_text(creases.sharpness_of_crease(after))}")
        for v in set(vertex_creases) | set(self.known_vertex_creases):
            before = self.known_vertex_creases.get(v, 0.0)
            after = vertex_creases.get(v, 0.0)
            if abs(before - after) > 1e-4:
                crease_changes[("v", v)] = (before, after)
                lines.append(f"corner v0:{v} {creases.sharpness_text(creases.sharpness_of_crease(after))}")
        return lines, points, crease_changes

    def limit_script(self, tessera):
        """Edit script lines for limit points the user moved in the limit
        object: a direct manipulation at the panel's edit level."""
        if self.limit_object is None or len(self.limit_points) == 0:
            return []
        points = mesh_objects.read_points(self.limit_object)
        if points.shape != self.limit_points.shape:
            return []
        moved = np.nonzero(np.any(np.abs(points - self.limit_points) > MOVE_EPSILON, axis=1))[0]
        lines = []
        for row in moved.tolist():
            packed = int(self.limit_ids[row])
            birth = tessera.id_level(packed)
            if birth > self.edit_level:
                raise ValueError(
                    f"limit point {tessera.format_vertex_id(packed)} is born at level {birth}: "
                    f"set the edit level to {birth} or more to move it")
            target = points[row]
            lines.append(f"move v{self.edit_level}:{tessera.id_index(packed)} to "
                         f"{target[0]!r} {target[1]!r} {target[2]!r}")
        return lines

    def send_changes(self, session, tessera):
        """Sends the cage's and the limit object's changes as one edit batch.
        Returns the Ack, or None when nothing changed."""
        try:
            lines, points, crease_changes = self.cage_script()
        except TopologyChanged:
            self.reset_cage()
            raise
        try:
            lines += self.limit_script(tessera)
        except ValueError:
            self.reset_cage()  # the limit object too: the refused move is not kept
            raise
        if not lines:
            return None
        try:
            ack = session.edit(self.document_id, "\n".join(lines) + "\n")
        except tessera.Rejected:
            self.reset_cage()
            raise
        self.known_points = points
        # One batch is one version (docs/PROTOCOL.md section 6.1): any other
        # step means someone else's edit came between, whose points the
        # cage must still be given.
        self.cage_version = ack.version if ack.version == self.cage_version + 1 else 0
        self.apply_crease_changes(crease_changes, after=True)
        self.undo_stack.append(Batch(ack.edit_ids or [ack.edit_id], crease_changes))
        self.redo_stack.clear()
        return ack

    def apply_crease_changes(self, changes, after):
        for key, (before, new) in changes.items():
            value = new if after else before
            if key[0] == "v":
                table, k = self.known_vertex_creases, key[1]
            else:
                table, k = self.known_edge_creases, key
            if value > 0.0:
                table[k] = value
            else:
                table.pop(k, None)

    def reset_cage(self):
        """Puts the last known server state back into the cage: after a
        refused edit, and after Blender's own undo and redo."""
        if self.cage_object is None:
            return
        if len(mesh_objects.read_points(self.cage_object)) != len(self.known_points):
            if self.cage_object.mode == "EDIT":
                return  # topology cannot be rewritten in Edit Mode; done when it is left
            mesh_objects.write_polygons(self.cage_object.data, self.known_points, self.faces)
        else:
            mesh_objects.write_cage_points(self.cage_object, self.known_points)
        self.write_known_creases()
        if self.limit_object is not None and len(self.limit_points):
            if len(mesh_objects.read_points(self.limit_object)) == len(self.limit_points):
                mesh_objects.write_cage_points(self.limit_object, self.limit_points)

    def undo(self, session):
        """Undoes this Blender's last batch on the server (every edit of it)."""
        if not self.undo_stack:
            raise ValueError(f"nothing of this Blender's to undo in '{self.name}'")
        batch = self.undo_stack[-1]
        script = "".join(f"undo {i}\n" for i in reversed(batch.edit_ids))
        session.edit(self.document_id, script)
        self.undo_stack.pop()
        self.redo_stack.append(batch)
        self.apply_crease_changes(batch.crease_changes, after=False)
        self.write_known_creases()
        self.cage_version = 0  # the points come back with the stream

    def redo(self, session):
        if not self.redo_stack:
            raise ValueError(f"nothing of this Blender's to redo in '{self.name}'")
        batch = self.redo_stack[-1]
        script = "".join(f"redo {i}\n" for i in batch.edit_ids)
        session.edit(self.document_id, script)
        self.redo_stack.pop()
        self.undo_stack.append(batch)
        self.apply_crease_changes(batch.crease_changes, after=True)
        self.write_known_creases()
        self.cage_version = 0

    # --- presence -------------------------------------------------------------

    def send_selection(self, session):
        """Tells the others which cage vertices are selected here."""
        if self.cage_object is None:
            return
        selection = mesh_objects.selected_vertices(self.cage_object)
        if selection != self.last_selection:
            session.select(self.document_id, [f"v0:{i}" for i in selection])
            self.last_selection = selection

    def presence_points(self, session, tessera):
        """[(participant name, (K, 3) world positions)] of the others'
        selected vertices, at their limit positions in the limit object."""
        if self.limit_object is None or len(self.limit_ids) == 0:
            return []
        index_of = {tessera.id_index(int(i)): row for row, i in enumerate(self.limit_ids.tolist())}
        matrix = np.array(self.limit_object.matrix_world)
        out = []
        for p in session.participants(self.document_id):
            if p.session_id == session.session_id or not p.selected_vertex_ids:
                continue
            rows = [index_of[tessera.id_index(i)] for i in p.selected_vertex_ids
                    if tessera.id_index(i) in index_of]
            local = self.limit_points[rows]
            world = local @ matrix[:3, :3].T + matrix[:3, 3]
            out.append((p.name, world))
        return out

