"""A Blender mesh as a Tessera base mesh: points, faces, creases, scheme.

Reads through bmesh, so an object in Edit Mode gives what the user sees.
Vertex and face order are kept: vertex i of the Blender mesh is `v0:i` of
the document (docs/PROTOCOL.md section 3.2, "Level 0").
"""

from dataclasses import dataclass, field

import bmesh
import numpy as np

from . import creases


@dataclass
class BaseMesh:
    points: np.ndarray                      # (N, 3) float64, the mesh's own coordinates
    faces: list                             # index lists, counter-clockwise
    edge_creases: dict = field(default_factory=dict)    # (a, b), a < b -> crease in (0, 1]
    vertex_creases: dict = field(default_factory=dict)  # vertex -> crease in (0, 1]


def open_bmesh(obj):
    """(bm, owned): the object's edit mesh in Edit Mode, else a copy to free."""
    if obj.mode == "EDIT":
        return bmesh.from_edit_mesh(obj.data), False
    bm = bmesh.new()
    bm.from_mesh(obj.data)
    return bm, True


def read_base_mesh(obj):
    """The object's mesh data (not its modifiers' result) as a BaseMesh."""
    if obj is None or obj.type != "MESH":
        raise ValueError(f"'{obj.name if obj else 'nothing'}' is not a mesh object")
    bm, owned = open_bmesh(obj)
    try:
        bm.verts.ensure_lookup_table()
        points = np.array([v.co[:] for v in bm.verts], dtype=np.float64).reshape(-1, 3)
        faces = [[v.index for v in f.verts] for f in bm.faces]
        edge_layer = bm.edges.layers.crease.active
        vert_layer = bm.verts.layers.crease.active
        edge_creases = {}
        if edge_layer is not None:
            for e in bm.edges:
                c = e[edge_layer]
                if c > 0.0:
                    a, b = e.verts[0].index, e.verts[1].index
                    edge_creases[(min(a, b), max(a, b))] = float(c)
        vertex_creases = {}
        if vert_layer is not None:
            for v in bm.verts:
                if v[vert_layer] > 0.0:
                    vertex_creases[v.index] = float(v[vert_layer])
    finally:
        if owned:
            bm.free()
    if len(faces) == 0:
        raise ValueError(f"mesh '{obj.data.name}' has no faces")
    return BaseMesh(points, faces, edge_creases, vertex_creases)


def boundary_edges(faces):
    """Edges used by one face only: always infinitely sharp in Tessera, which
    refuses a tag on them (docs/PROTOCOL.md, SetEdgeSharpness)."""
    uses = {}
    for face in faces:
        n = len(face)
        for j in range(n):
            a, b = face[j], face[(j + 1) % n]
            key = (min(a, b), max(a, b))
            uses[key] = uses.get(key, 0) + 1
    return {key for key, count in uses.items() if count == 1}


def tag_file_text(mesh):
    """The creases as a tag file (docs/FORMATS.md): `crease I J S` per
    creased interior edge, `corner I S` per creased vertex."""
    boundary = boundary_edges(mesh.faces)
    lines = []
    for (a, b), c in sorted(mesh.edge_creases.items()):
        if (a, b) not in boundary:
            lines.append(f"crease {a} {b} {creases.sharpness_text(creases.sharpness_of_crease(c))}")
    for v, c in sorted(mesh.vertex_creases.items()):
        lines.append(f"corner {v} {creases.sharpness_text(creases.sharpness_of_crease(c))}")
    return "\n".join(lines) + ("\n" if lines else "")


def choose_scheme(obj, mesh, offered=("loop", "catmull-clark")):
    """The scheme a new document gets, from the object's Subdivision Surface
    modifier: Catmull-Clark asks for catmull-clark; Simple has no smooth
    counterpart on the server (documents are Loop or Catmull-Clark,
    README "Hierarchical documents"), so it, like no modifier at all, gets
    Loop for an all-triangle mesh and catmull-clark otherwise."""
    for modifier in obj.modifiers:
        if modifier.type == "SUBSURF":
            if modifier.subdivision_type == "CATMULL_CLARK" and "catmull-clark" in offered:
                return "catmull-clark", f"from the modifier '{modifier.name}' (Catmull-Clark)"
            break
    if all(len(f) == 3 for f in mesh.faces):
        return "loop", "all faces are triangles"
    return "catmull-clark", "the mesh has faces that are not triangles"
