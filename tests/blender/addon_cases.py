"""The Blender add-on's tests, run inside Blender by run_blender_case.py:
`blender -b --factory-startup --python addon_cases.py -- CASE ROOT`.

Each case installs the add-on from its zip (as a user would, with
Preferences > Add-ons > Install), enables it, starts a real tessera-server,
drives the add-on through its operators and the functions its timer calls
(a background Blender runs no timers), and checks the server's side with a
second, plain `tessera` session and the `tessera` CLI. Expected surfaces
come from core's offline refinement (tessera.refine) of meshes and tag
files written out here by hand, never from the add-on.
"""

import json
import math
import os
import struct
import subprocess
import sys
import time
import traceback

import bmesh
import bpy
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from server_process import ADMIN_TOKEN, Server  # noqa: E402

WAIT_SECONDS = 10

# A closed octahedron of eight triangles: a Loop document.
OCTAHEDRON_POINTS = [(1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1)]
OCTAHEDRON_FACES = [(0, 2, 4), (2, 1, 4), (1, 3, 4), (3, 0, 4), (2, 0, 5), (1, 2, 5), (3, 1, 5), (0, 3, 5)]
# Its creases in Blender: edge 0-2 crease 1 (sharpness 10 c^2 = 10: infinite),
# edge 2-4 crease 0.5 (2.5), vertex 5 crease 1 (an infinitely sharp vertex).
OCTAHEDRON_TAGS = "crease 0 2 inf\ncrease 2 4 2.5\ncorner 5 inf\n"


def check(condition, message):
    if not condition:
        raise AssertionError(message)


def glb_positions(glb):
    """POSITION of a GLB's first primitive (written here again, apart from
    the add-on's reader, so that the check does not trust it)."""
    json_length = struct.unpack_from("<I", glb, 12)[0]
    doc = json.loads(glb[20:20 + json_length])
    binary = glb[20 + json_length + 8:]
    accessor = doc["accessors"][doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"]]
    view = doc["bufferViews"][accessor["bufferView"]]
    start = view.get("byteOffset", 0) + accessor.get("byteOffset", 0)
    check(view.get("byteStride", 12) == 12, "positions are packed")
    return np.frombuffer(binary, "<f4", accessor["count"] * 3, start).reshape(-1, 3).astype(float)


def install_addon(root):
    zip_path = os.environ["TESSERA_BLENDER_ZIP"]
    result = bpy.ops.preferences.addon_install(filepath=zip_path)
    check(result == {"FINISHED"}, f"installing {zip_path}: {result}")
    result = bpy.ops.preferences.addon_enable(module="tessera_blender")
    check(result == {"FINISHED"}, f"enabling tessera_blender: {result}")
    import tessera_blender

    check(tessera_blender.__file__.startswith(os.path.join(root, "scripts")),
          f"the add-on runs from the installed zip, not {tessera_blender.__file__}")
    return tessera_blender


def addon_modules():
    from tessera_blender import connection, handlers, presence_draw

    return connection.CONNECTION, handlers, presence_draw


def run(operator):
    """An operator's result; one that reports an error raises RuntimeError
    when called from Python, which is its CANCELLED."""
    try:
        return operator()
    except RuntimeError as e:
        print(f"(reported) {e}")
        return {"CANCELLED"}


def connect(port, token=ADMIN_TOKEN, name="blender"):
    s = bpy.context.scene.tessera
    s.host, s.port, s.token, s.client_name = "127.0.0.1", port, token, name
    return run(bpy.ops.tessera.connect)


def plain_client(port, name="second"):
    import tessera  # importable once the add-on found it (configured_paths.py)

    return tessera, tessera.Session.connect("127.0.0.1", port, ADMIN_TOKEN, name=name, timeout=10)


def octahedron_object(name="octahedron"):
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata(OCTAHEDRON_POINTS, [], OCTAHEDRON_FACES)
    mesh.update()
    bm = bmesh.new()
    bm.from_mesh(mesh)
    edge_layer = bm.edges.layers.crease.verify()
    vert_layer = bm.verts.layers.crease.verify()
    bm.verts.ensure_lookup_table()
    for e in bm.edges:
        ends = {e.verts[0].index, e.verts[1].index}
        if ends == {0, 2}:
            e[edge_layer] = 1.0
        elif ends == {2, 4}:
            e[edge_layer] = 0.5
    bm.verts[5][vert_layer] = 1.0
    bm.to_mesh(mesh)
    bm.free()
    return activate(bpy.data.objects.new(name, mesh))


def activate(obj):
    if obj.name not in bpy.context.scene.collection.objects:
        bpy.context.scene.collection.objects.link(obj)
    for other in bpy.context.view_layer.objects:
        other.select_set(False)
    bpy.context.view_layer.objects.active = obj
    obj.select_set(True)
    return obj


def quad_cube_object(name="cube", modifier=True):
    bpy.ops.mesh.primitive_cube_add(size=2.0)
    obj = bpy.context.active_object
    obj.name = name
    if modifier:
        obj.modifiers.new("Subdivision", "SUBSURF")
    return obj


def expected_limit(tessera, root, points, tags, level):
    path = os.path.join(root, "expected.tags")
    with open(path, "w") as f:
        f.write(tags)
    return tessera.refine(np.asarray(points, float), np.asarray(OCTAHEDRON_FACES), level=level,
                          limit=True, tags=path).positions


def server_limit(session, document_id, level):
    _, glb = session.export_document(document_id, level, limit=True)
    return glb_positions(glb)


def wait_until(predicate, poll, what):
    deadline = time.monotonic() + WAIT_SECONDS
    while time.monotonic() < deadline:
        poll()
        if predicate():
            return
        time.sleep(0.02)
    raise AssertionError(f"not within {WAIT_SECONDS} s: {what}")


# --- cases ---------------------------------------------------------------------


def case_create_with_creases(root, server):
    """A bpy mesh with edge and vertex creases becomes a Loop document
    whose limit surface is the one of the creases as tags; a triangle mesh
    with a Catmull-Clark modifier becomes a catmull-clark document; an
    object that is not a mesh is refused by name."""
    check(connect(server.port) == {"FINISHED"}, "connect")
    connection, _, _ = addon_modules()
    obj = octahedron_object()
    check(bpy.ops.tessera.create_from_mesh() == {"FINISHED"}, f"create: {connection.message}")
    doc = next(iter(connection.documents.values()))
    check(doc.scheme == "loop", f"an all-triangle mesh without modifier is Loop, got {doc.scheme}")
    check(doc.cage_object is not None and doc.limit_object is not None, "two objects")
    check(len(doc.cage_object.data.polygons) == 8, "the cage has the octahedron's faces")
    tessera, second = plain_client(server.port)
    second.open_document(doc.document_id)
    got = server_limit(second, doc.document_id, 2)
    want = expected_limit(tessera, root, OCTAHEDRON_POINTS, OCTAHEDRON_TAGS, 2)
    untagged = expected_limit(tessera, root, OCTAHEDRON_POINTS, "", 2)
    check(got.shape == want.shape, f"{got.shape} limit points, want {want.shape}")
    error = np.abs(got - want).max()
    check(error < 1e-5, f"the server's limit differs from the tagged one by {error}")
    # Both begin with the level's vertices in order; the tagged one's
    # vertices split along sharp features for their normals follow.
    vertices = len(untagged)
    check(np.abs(untagged - want[:vertices]).max() > 1e-2, "the tags change the surface (the check can fail)")
    # Shown back as Blender creases on the cage.
    from tessera_blender import mesh_objects

    edges, verts = mesh_objects.read_creases(doc.cage_object)
    check(edges == {(0, 2): 1.0, (2, 4): 0.5} and verts == {5: 1.0}, f"cage creases {edges} {verts}")

    tri = octahedron_object("triangles with Catmull-Clark")
    tri.modifiers.new("Subdivision", "SUBSURF")
    check(bpy.ops.tessera.create_from_mesh() == {"FINISHED"}, f"create: {connection.message}")
    catmark = connection.documents[max(connection.documents)]
    check(catmark.scheme == "catmull-clark", f"the modifier asks for catmull-clark, got {catmark.scheme}")
    second.open_document(catmark.document_id)
    _, sizes, _ = second.cage(catmark.document_id, 1)
    check(set(sizes.tolist()) == {4}, "level 1 of the server's document is quads (Catmull-Clark)")

    bpy.ops.object.empty_add()
    check(run(bpy.ops.tessera.create_from_mesh) == {"CANCELLED"}, "an empty is refused")
    check("'Empty' is not a mesh object" in connection.message, f"message: {connection.message}")
    second.close()


def case_cage_move(root, server):
    """A cage vertex moved and an edge creased in bpy reach the server as
    one edit batch, and a second client's subscription; Tessera's undo
    takes them back; Blender's undo only resets the cage."""
    check(connect(server.port) == {"FINISHED"}, "connect")
    connection, handlers, _ = addon_modules()
    octahedron_object()
    check(bpy.ops.tessera.create_from_mesh() == {"FINISHED"}, f"create: {connection.message}")
    doc = next(iter(connection.documents.values()))
    tessera, second = plain_client(server.port)
    second.open_document(doc.document_id)
    second.subscribe(doc.document_id, base_level=1, max_level=1)
    first = second.wait_for(doc.document_id, timeout=WAIT_SECONDS)
    before = first.version
    top_before = first.positions()[first.vertex_ids() == tessera.vertex_id("v0:4")][0]

    cage = activate(doc.cage_object)
    cage.data.vertices[4].co.z += 0.5
    bm = bmesh.new()
    bm.from_mesh(cage.data)
    layer = bm.edges.layers.crease.verify()
    for e in bm.edges:
        if {e.verts[0].index, e.verts[1].index} == {0, 3}:
            e[layer] = 1.0
    bm.to_mesh(cage.data)
    bm.free()
    check(bpy.ops.tessera.send_edits() == {"FINISHED"}, f"send: {connection.message}")

    view = second.wait_for(doc.document_id, version=before + 1, timeout=WAIT_SECONDS)
    check(view.version == before + 1, f"one batch is one version: {before} -> {view.version}")
    moved = [list(p) for p in OCTAHEDRON_POINTS]
    moved[4][2] += 0.5
    got = server_limit(second, doc.document_id, 2)
    want = expected_limit(tessera, root, moved, OCTAHEDRON_TAGS + "crease 0 3 inf\n", 2)
    error = np.abs(got - want).max()
    check(error < 1e-5, f"after the move and crease the server's limit differs by {error}")
    ids = view.vertex_ids()
    top = view.positions()[ids == tessera.vertex_id("v0:4")]
    check(len(top) and top[0][2] > top_before[2] + 0.1, f"the second client sees v0:4 moved: {top_before} -> {top}")

    check(bpy.ops.tessera.undo() == {"FINISHED"}, f"undo: {connection.message}")
    got = server_limit(second, doc.document_id, 2)
    want = expected_limit(tessera, root, OCTAHEDRON_POINTS, OCTAHEDRON_TAGS, 2)
    check(np.abs(got - want).max() < 1e-5, "Tessera's undo restores the server's surface")
    wait_until(lambda: abs(cage.data.vertices[4].co.z - 1.0) < 1e-6, connection.poll,
               "the cage shows the undone move")

    # Blender's undo (its undo_post handler): the cage goes back to the
    # server's state and nothing is sent.
    version = second.list_documents()[0].version
    cage.data.vertices[1].co.x -= 0.75
    handlers.after_blender_undo()
    check(abs(cage.data.vertices[1].co.x + 1.0) < 1e-6, "Blender's undo resets the cage to the server's")
    check(bpy.ops.tessera.send_edits() == {"FINISHED"}, "send")
    check(second.list_documents()[0].version == version, "Blender's undo sent no edit")
    second.close()


def case_stream_to_limit(root, server):
    """A second client's edit changes the add-on's limit mesh and cage; the
    limit mesh equals `tessera remote export --limit` within the
    quantization bound (docs/REGION_ENCODING.md, "Quantization error");
    the second client's selection is drawn and listed."""
    check(connect(server.port) == {"FINISHED"}, "connect")
    connection, _, presence_draw = addon_modules()
    quad_cube_object()
    bpy.context.scene.tessera.lod = 2
    check(bpy.ops.tessera.create_from_mesh() == {"FINISHED"}, f"create: {connection.message}")
    doc = next(iter(connection.documents.values()))
    check(doc.scheme == "catmull-clark", f"scheme {doc.scheme}")
    tessera, second = plain_client(server.port)
    second.open_document(doc.document_id)
    corner = doc.known_points[6].copy()
    corner_limit = doc.limit_points[doc.limit_ids == tessera.vertex_id("v0:6")][0].copy()
    ack = second.offset_vertices(doc.document_id, "v0:6", (0.0, 0.0, 0.3))
    second.select(doc.document_id, ["v0:6"])
    wait_until(lambda: doc.limit_version >= ack.version, connection.poll, "the add-on sees the edit")
    wait_until(lambda: abs(doc.cage_object.data.vertices[6].co.z - (corner[2] + 0.3)) < 1e-6,
               connection.poll, "the cage shows the second client's move")

    out = os.path.join(root, "limit.glb")
    cli = [os.environ["TESSERA_CLI"], "remote", "--port", str(server.port), "--token-file",
           server.token_file, "export", str(doc.document_id), "--level", "2", "--limit", "-o", out]
    subprocess.run(cli, check=True, timeout=WAIT_SECONDS, stdout=subprocess.DEVNULL)
    exported = glb_positions(open(out, "rb").read())
    mesh = doc.limit_object.data
    points = np.empty(len(mesh.vertices) * 3, np.float32)
    mesh.vertices.foreach_get("co", points)
    points = points.reshape(-1, 3).astype(float)
    index = np.empty(len(mesh.vertices), np.int32)
    mesh.attributes["tessera_id_index"].data.foreach_get("value", index)
    # Every vertex of level 2 once (a cube without creases splits none).
    check(sorted(index.tolist()) == list(range(len(exported))),
          f"{len(points)} limit points, the export has {len(exported)}")
    diagonal = np.linalg.norm(exported.max(0) - exported.min(0))
    bound = 1e-4 * diagonal
    error = np.abs(points - exported[index]).max()
    check(error <= bound, f"limit mesh vs export: {error} > bound {bound}")
    check(points[index == 6][0][2] > corner_limit[2] + 0.1, "the moved corner's limit went up")

    wait_until(lambda: any(name == "second" for _, name, _ in presence_draw.presence()),
               connection.poll, "the second client's selection")
    (_, name, drawn), = presence_draw.presence()
    check(np.abs(drawn[0] - exported[6]).max() <= bound, f"selection drawn at {drawn[0]}, not {exported[6]}")
    names = {p.name for p in connection.session.participants(doc.document_id)}
    check(names == {"blender", "second"}, f"participants {names}")
    second.close()


def case_token_and_restart(root, server):
    """A wrong token is refused with a message naming it; a server that
    goes away is reported, and the add-on reconnects when it is back and
    shows the edits made then."""
    connection, _, _ = addon_modules()
    check(connect(server.port, token="not-the-token-of-this-server") == {"CANCELLED"}, "wrong token")
    check("refused the token" in connection.message, f"message: {connection.message}")
    check(connect(server.port) == {"FINISHED"}, f"connect: {connection.message}")
    check(connection.message.startswith("Connected"), connection.message)
    octahedron_object()
    check(bpy.ops.tessera.create_from_mesh() == {"FINISHED"}, f"create: {connection.message}")
    doc = next(iter(connection.documents.values()))

    server.stop()
    wait_until(lambda: connection.lost, connection.poll, "the add-on notices the server is gone")
    check("lost" in connection.message and str(server.port) in connection.message, connection.message)
    check(run(bpy.ops.tessera.list_documents) == {"CANCELLED"}, "no list without a server")
    server.start()
    wait_until(lambda: connection.connected, connection.poll, "the add-on reconnects")
    check(connection.message.startswith("Reconnected"), connection.message)
    tessera, second = plain_client(server.port)
    second.open_document(doc.document_id)
    ack = second.offset_vertices(doc.document_id, "v0:4", (0.0, 0.0, 0.5))
    wait_until(lambda: doc.limit_version >= ack.version, connection.poll, "the edit after the restart")
    wait_until(lambda: abs(doc.cage_object.data.vertices[4].co.z - 1.5) < 1e-6, connection.poll,
               "the cage after the restart")
    second.close()


def case_open_and_limit_move(root, server):
    """A document made elsewhere is listed and opened as a cage (the file's
    points and quads) and a limit surface at the panel's LOD; a limit point
    moved in the limit object lands there (a direct manipulation at the
    panel's edit level); a level too coarse for the point is refused by name."""
    tessera_dir = os.path.dirname(os.path.dirname(HERE))
    check(connect(server.port) == {"FINISHED"}, "connect")
    connection, _, _ = addon_modules()
    tessera, second = plain_client(server.port)
    sample = os.path.join(tessera_dir, "deploy", "samples", "quad_cube.obj")
    made = second.create_document(sample, name="quad cube", max_level=3)
    check(run(bpy.ops.tessera.list_documents) == {"FINISHED"}, f"list: {connection.message}")
    check([d.name for d in connection.listed] == ["quad cube"], f"listed {connection.listed}")
    settings = bpy.context.scene.tessera
    settings.document = str(made.document_id)
    settings.lod, settings.edit_level = 2, 2
    check(run(bpy.ops.tessera.open_document) == {"FINISHED"}, f"open: {connection.message}")
    doc = connection.documents[made.document_id]
    with open(sample) as f:
        file_points = [[float(x) for x in line.split()[1:4]] for line in f if line.startswith("v ")]
    cage_points = np.array([v.co[:] for v in doc.cage_object.data.vertices])
    check(np.abs(cage_points - np.array(file_points)).max() < 1e-6, "the cage is the file's points")
    check({len(p.vertices) for p in doc.cage_object.data.polygons} == {4}, "the cage's faces are quads")
    levels = np.empty(len(doc.limit_object.data.vertices), np.int32)
    doc.limit_object.data.attributes["tessera_id_level"].data.foreach_get("value", levels)
    check(levels.max() == 2, f"the limit surface is at LOD 2 (birth levels up to {levels.max()})")

    # A point born at level 1, edited at level 2 (the panel's edit level).
    row = int(np.nonzero(levels == 1)[0][0])
    index = tessera.id_index(int(doc.limit_ids[row]))
    mesh = doc.limit_object.data
    target = np.array(mesh.vertices[row].co[:]) + (0.0, 0.0, 0.2)
    mesh.vertices[row].co = target
    activate(doc.limit_object)
    check(run(bpy.ops.tessera.send_edits) == {"FINISHED"}, f"send: {connection.message}")
    second.open_document(made.document_id)
    got = server_limit(second, made.document_id, 2)[index]
    check(np.abs(got - target).max() < 1e-5, f"limit v2:{index} at {got}, moved to {target}")

    # Edit level 0 cannot name a vertex born at level 2.
    settings.edit_level = 0
    check(run(bpy.ops.tessera.apply_lod) == {"FINISHED"}, "apply")
    wait_until(lambda: doc.limit_version >= 2, connection.poll, "the limit surface after the move")
    born = np.array([tessera.id_level(int(i)) for i in doc.limit_ids])
    row = int(np.nonzero(born == 2)[0][0])
    mesh.vertices[row].co.z += 0.2
    check(run(bpy.ops.tessera.send_edits) == {"CANCELLED"}, "a level-2 point at edit level 0")
    check("born at level 2" in connection.message, connection.message)
    second.close()


def case_install_rules(root, server):
    """`cmake --install --component tessera_blender` (run_blender_case.py
    ran it into ROOT/prefix) gives an add-on Blender enables from its
    system scripts folder, which finds the tessera package and connects."""
    import addon_utils

    addon_utils.enable("tessera_blender", default_set=True)
    import tessera_blender

    check(tessera_blender.__file__.startswith(os.path.join(root, "prefix")),
          f"the add-on runs from the install, not {tessera_blender.__file__}")
    check(connect(server.port) == {"FINISHED"}, "connect")


CASES = {
    "create_with_creases": case_create_with_creases,
    "cage_move": case_cage_move,
    "stream_to_limit": case_stream_to_limit,
    "token_and_restart": case_token_and_restart,
    "open_and_limit_move": case_open_and_limit_move,
    "install_rules": case_install_rules,
}


def main():
    argv = sys.argv[sys.argv.index("--") + 1:]
    case, root = argv[0], argv[1]
    bpy.ops.wm.read_factory_settings(use_empty=True)
    if case != "install_rules":
        install_addon(root)
    server = Server(os.environ["TESSERA_SERVER"], root)
    try:
        CASES[case](root, server)
    except BaseException:
        traceback.print_exc()
        print(f"FAILED {case}\n--- server log ---\n{server.log()}")
        code = 1
    else:
        print(f"PASSED {case}")
        code = 0
    finally:
        try:
            from tessera_blender.connection import CONNECTION

            CONNECTION.disconnect()
        except Exception:
            pass
        server.stop()
    sys.stdout.flush()
    os._exit(code)


main()
