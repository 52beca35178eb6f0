"""Writing the two objects of an opened document into Blender.

The control cage keeps its topology for the document's life (edits move
points and set tags, docs/PROTOCOL.md section 17 "Topology only"), so it
is written once and then only its points and creases change. The limit
surface is rewritten whole from the stream's regions at each version.
Both work in Object Mode (mesh data) and in Edit Mode (bmesh), so an
update never forces the user out of Edit Mode.
"""

import bmesh
import bpy
import numpy as np

ID_LEVEL = "tessera_id_level"
ID_INDEX = "tessera_id_index"


def new_object(name, mesh_name, collection=None, matrix=None):
    mesh = bpy.data.meshes.new(mesh_name)
    obj = bpy.data.objects.new(name, mesh)
    (collection or bpy.context.scene.collection).objects.link(obj)
    if matrix is not None:
        obj.matrix_world = matrix
    return obj


def write_polygons(mesh, points, faces):
    """Replaces mesh's geometry by points (N, 3) and faces (index lists)."""
    mesh.clear_geometry()
    sizes = np.fromiter((len(f) for f in faces), dtype=np.int32, count=len(faces))
    corners = np.fromiter((i for f in faces for i in f), dtype=np.int32, count=int(sizes.sum()))
    starts = np.zeros(len(faces), dtype=np.int32)
    if len(faces):
        starts[1:] = np.cumsum(sizes)[:-1]
    mesh.vertices.add(len(points))
    mesh.vertices.foreach_set("co", np.asarray(points, dtype=np.float32).ravel())
    mesh.loops.add(len(corners))
    mesh.loops.foreach_set("vertex_index", corners)
    mesh.polygons.add(len(faces))
    mesh.polygons.foreach_set("loop_start", starts)
    mesh.polygons.foreach_set("loop_total", sizes)
    mesh.update(calc_edges=True)
    mesh.validate(clean_customdata=False)


def write_cage_points(obj, points):
    """Moves the cage's vertices to points (N, 3), in either mode."""
    if obj.mode == "EDIT":
        bm = bmesh.from_edit_mesh(obj.data)
        bm.verts.ensure_lookup_table()
        for v, p in zip(bm.verts, points):
            v.co = p
        bmesh.update_edit_mesh(obj.data, loop_triangles=False, destructive=False)
    else:
        obj.data.vertices.foreach_set("co", np.asarray(points, dtype=np.float32).ravel())
        obj.data.update()


def write_cage_creases(obj, edge_creases, vertex_creases):
    """Sets every edge's and vertex's crease: those named get their value,
    the others 0. edge_creases: (a, b) with a < b -> crease."""
    owned = obj.mode != "EDIT"
    if owned:
        bm = bmesh.new()
        bm.from_mesh(obj.data)
    else:
        bm = bmesh.from_edit_mesh(obj.data)
    edge_layer = bm.edges.layers.crease.verify()
    vert_layer = bm.verts.layers.crease.verify()
    for e in bm.edges:
        a, b = e.verts[0].index, e.verts[1].index
        e[edge_layer] = edge_creases.get((min(a, b), max(a, b)), 0.0)
    for v in bm.verts:
        v[vert_layer] = vertex_creases.get(v.index, 0.0)
    if owned:
        bm.to_mesh(obj.data)
        bm.free()
        obj.data.update()
    else:
        bmesh.update_edit_mesh(obj.data, loop_triangles=False, destructive=False)


def write_limit_surface(obj, points, triangles, levels, indices):
    """Rewrites the limit object: points (N, 3), triangles (M, 3), and per
    vertex the birth level and index of the control vertex whose limit it
    is (docs/PROTOCOL.md section 6.2), as the integer point attributes
    tessera_id_level and tessera_id_index."""
    if obj.mode == "EDIT":
        bm = bmesh.from_edit_mesh(obj.data)
        bm.clear()
        level_layer = bm.verts.layers.int.get(ID_LEVEL) or bm.verts.layers.int.new(ID_LEVEL)
        index_layer = bm.verts.layers.int.get(ID_INDEX) or bm.verts.layers.int.new(ID_INDEX)
        verts = [bm.verts.new(p) for p in points]
        for v, level, index in zip(verts, levels, indices):
            v[level_layer] = int(level)
            v[index_layer] = int(index)
        for t in triangles:
            bm.faces.new((verts[t[0]], verts[t[1]], verts[t[2]]))
        bmesh.update_edit_mesh(obj.data)
        return
    mesh = obj.data
    write_polygons(mesh, points, np.asarray(triangles).tolist())
    # A limit surface is smooth: shade it so (its normals follow the mesh).
    mesh.polygons.foreach_set("use_smooth", np.ones(len(mesh.polygons), dtype=bool))
    for name, values in ((ID_LEVEL, levels), (ID_INDEX, indices)):
        attribute = mesh.attributes.get(name) or mesh.attributes.new(name, "INT", "POINT")
        attribute.data.foreach_set("value", np.asarray(values, dtype=np.int32))
    mesh.update()


def read_points(obj):
    """(N, 3) float64 vertex positions of a mesh object, in either mode."""
    if obj.mode == "EDIT":
        bm = bmesh.from_edit_mesh(obj.data)
        return np.array([v.co[:] for v in bm.verts], dtype=np.float64).reshape(-1, 3)
    points = np.empty(len(obj.data.vertices) * 3, dtype=np.float32)
    obj.data.vertices.foreach_get("co", points)
    return points.reshape(-1, 3).astype(np.float64)


def read_creases(obj):
    """(edge creases {(a, b): c}, vertex creases {v: c}), nonzero ones."""
    from .base_mesh import open_bmesh

    bm, owned = open_bmesh(obj)
    try:
        edge_layer = bm.edges.layers.crease.active
        vert_layer = bm.verts.layers.crease.active
        edges, verts = {}, {}
        if edge_layer is not None:
            for e in bm.edges:
                if e[edge_layer] > 0.0:
                    a, b = e.verts[0].index, e.verts[1].index
                    edges[(min(a, b), max(a, b))] = float(e[edge_layer])
        if vert_layer is not None:
            for v in bm.verts:
                if v[vert_layer] > 0.0:
                    verts[v.index] = float(v[vert_layer])
        return edges, verts
    finally:
        if owned:
            bm.free()


def selected_vertices(obj):
    """Indices of the selected vertices, in either mode."""
    if obj.mode == "EDIT":
        bm = bmesh.from_edit_mesh(obj.data)
        return [v.index for v in bm.verts if v.select]
    flags = np.zeros(len(obj.data.vertices), dtype=bool)
    obj.data.vertices.foreach_get("select", flags)
    return np.nonzero(flags)[0].tolist()

