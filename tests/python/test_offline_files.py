"""Offline files: write_mesh, read_tags and write_tags (docs/PYTHON.md
"Offline"). Written files are read here by readers written from the
formats' own descriptions (OFF and OBJ text, binary PLY 1.0, binary STL,
glTF 2.0's GLB container), not by Tessera's importers; the tag files by a
line splitter following docs/FORMATS.md "Tag sidecar files". Round trips
through read_mesh compare with the input arrays."""

import json
import math
import struct

import numpy as np
import pytest

import tessera
from conftest import SAMPLES

# Decimals that are not binary fractions: a lossless writer must keep them.
POINTS = np.array([[0.1, 0.0, 0.0], [1.0, 1 / 3, 0.0], [0.0, 1.0, 2 / 7], [0.0, 0.0, 1.0]])
TRIANGLES = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
# The unit cube as six quads, outward.
CUBE = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], dtype=np.float64)
QUADS = [[0, 1, 3, 2], [4, 6, 7, 5], [0, 4, 5, 1], [2, 3, 7, 6], [0, 2, 6, 4], [1, 5, 7, 3]]


def text_lines(path):
    return [line.split() for line in path.read_text().splitlines() if line.strip() and not line.startswith("#")]


def unit(v):
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


def test_off_is_written_losslessly(tmp_path):
    path = tmp_path / "tet.off"
    tessera.write_mesh(path, POINTS, TRIANGLES)
    lines = text_lines(path)
    assert lines[0] == ["OFF"]
    assert [int(n) for n in lines[1]] == [4, 4, 0]
    assert np.array_equal(np.array([[float(x) for x in line] for line in lines[2:6]]), POINTS)
    assert [[int(x) for x in line] for line in lines[6:10]] == [[3, *t] for t in TRIANGLES.tolist()]


def test_obj_has_points_normals_and_polygons(tmp_path):
    normals = unit(POINTS - POINTS.mean(axis=0))
    path = tmp_path / "tet.obj"
    tessera.write_mesh(str(path), POINTS, TRIANGLES, normals=normals)
    lines = text_lines(path)
    v = np.array([[float(x) for x in l[1:]] for l in lines if l[0] == "v"])
    vn = np.array([[float(x) for x in l[1:]] for l in lines if l[0] == "vn"])
    faces = [[int(c.split("/")[0]) - 1 for c in l[1:]] for l in lines if l[0] == "f"]
    assert np.array_equal(v, POINTS) and np.array_equal(vn, normals)
    assert faces == TRIANGLES.tolist()

    quads = tmp_path / "cube.obj"
    tessera.write_mesh(quads, CUBE, QUADS)
    faces = [[int(c.split("/")[0]) - 1 for c in l[1:]] for l in text_lines(quads) if l[0] == "f"]
    assert faces == QUADS  # polygons kept as they are


def test_binary_ply_has_float32_points_and_the_faces(tmp_path):
    path = tmp_path / "cube.ply"
    tessera.write_mesh(path, CUBE, QUADS)
    data = path.read_bytes()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode().splitlines()
    assert header[0] == "ply" and header[1] == "format binary_little_endian 1.0"
    assert "element vertex 8" in header and "element face 6" in header
    assert "property list uchar int vertex_indices" in header
    body = data[end:]
    vertices = np.frombuffer(body, dtype="<f4", count=8 * 3).reshape(8, 3)
    assert np.array_equal(vertices, CUBE.astype(np.float32))
    at, faces = 8 * 12, []
    for _ in range(6):
        n = body[at]
        faces.append(list(struct.unpack_from(f"<{n}i", body, at + 1)))
        at += 1 + 4 * n
    assert faces == QUADS and at == len(body)


def test_binary_stl_has_each_facets_corners_and_unit_normal(tmp_path):
    path = tmp_path / "cube.stl"
    tessera.write_mesh(path, CUBE, QUADS)
    data = path.read_bytes()
    (count,) = struct.unpack_from("<I", data, 80)
    assert count == 12 and len(data) == 84 + 50 * count  # six quads, two triangles each
    records = np.frombuffer(data[84:], dtype=np.dtype([("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")]))
    # Each quad (a, b, c, d) as the fan (a, b, c), (a, c, d), in order.
    fans = [[q[0], q[k], q[k + 1]] for q in QUADS for k in (1, 2)]
    assert np.array_equal(records["v"], CUBE[fans].astype(np.float32))
    corners = CUBE[fans]
    expected = unit(np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0]))
    assert np.allclose(records["n"], expected, atol=1e-7)


def glb_arrays(path):
    """POSITION, NORMAL and the indices of a GLB's first primitive, read as
    the glTF 2.0 specification lays them out."""
    data = path.read_bytes()
    magic, version, length = struct.unpack_from("<4sII", data, 0)
    assert (magic, version, length) == (b"glTF", 2, len(data))
    json_length, json_type = struct.unpack_from("<I4s", data, 12)
    assert json_type == b"JSON"
    gltf = json.loads(data[20 : 20 + json_length])
    bin_at = 20 + json_length
    bin_length, bin_type = struct.unpack_from("<I4s", data, bin_at)
    assert bin_type == b"BIN\x00"
    blob = data[bin_at + 8 : bin_at + 8 + bin_length]
    types = {5126: "<f4", 5125: "<u4", 5123: "<u2"}
    widths = {"VEC3": 3, "SCALAR": 1}

    def accessor(index):
        a = gltf["accessors"][index]
        view = gltf["bufferViews"][a["bufferView"]]
        start = view.get("byteOffset", 0) + a.get("byteOffset", 0)
        n = a["count"] * widths[a["type"]]
        return np.frombuffer(blob, dtype=types[a["componentType"]], count=n, offset=start)

    primitive = gltf["meshes"][0]["primitives"][0]
    attributes = primitive["attributes"]
    normals = accessor(attributes["NORMAL"]).reshape(-1, 3) if "NORMAL" in attributes else None
    return accessor(attributes["POSITION"]).reshape(-1, 3), normals, accessor(primitive["indices"]).reshape(-1, 3)


def test_glb_holds_the_points_and_triangles(tmp_path):
    normals = unit(POINTS - POINTS.mean(axis=0))
    path = tmp_path / "tet.glb"
    tessera.write_mesh(path, POINTS, TRIANGLES, normals=normals)
    positions, read_normals, indices = glb_arrays(path)
    assert np.array_equal(positions, POINTS.astype(np.float32))
    assert np.allclose(read_normals, normals, atol=1e-7)
    assert np.array_equal(indices, TRIANGLES)


@pytest.mark.parametrize("extension", [".obj", ".off", ".ply", ".glb", ".usda"])
def test_a_refined_mesh_reads_back_as_written(tmp_path, extension):
    mesh = tessera.refine(POINTS, TRIANGLES, level=2, limit=True)
    path = tmp_path / ("level2" + extension)
    tessera.write_mesh(path, mesh)  # a tessera.Mesh, with its normals
    back = tessera.read_mesh(str(path))
    # OBJ, OFF and USDA keep doubles; PLY and GLB store float32.
    lossless = extension in (".obj", ".off", ".usda")
    expected = mesh.positions if lossless else mesh.positions.astype(np.float32).astype(np.float64)
    assert np.array_equal(back.positions, expected)
    assert np.array_equal(back.triangles, mesh.triangles)


def test_a_polygon_mesh_round_trips_its_quads(tmp_path):
    level1 = tessera.refine(CUBE, QUADS, level=1, scheme="catmull-clark")
    path = tmp_path / "cc.obj"
    tessera.write_mesh(path, level1)
    again = tessera.refine(str(path), level=0, scheme="catmull-clark")
    assert np.array_equal(again.positions, level1.positions)
    assert np.array_equal(again.polygon_offsets, level1.polygon_offsets)
    assert np.array_equal(again.polygon_corners, level1.polygon_corners)


def test_write_mesh_refuses_what_it_cannot_write_and_writes_nothing(tmp_path):
    with pytest.raises(tessera.Error) as extension:
        tessera.write_mesh(tmp_path / "tet.xyz", POINTS, TRIANGLES)
    assert extension.value.code == "unsupported" and ".xyz" in str(extension.value)
    bad = tmp_path / "bad.obj"
    with pytest.raises(tessera.Error) as index:
        tessera.write_mesh(bad, POINTS, [[0, 1, 9]])
    assert index.value.code == "invalid mesh" and "9" in str(index.value)
    with pytest.raises(tessera.Error) as normals:
        tessera.write_mesh(bad, POINTS, TRIANGLES, normals=np.ones((3, 3)))
    assert normals.value.code == "invalid mesh"
    assert not bad.exists()
    with pytest.raises(tessera.Error) as draco:
        tessera.write_mesh(tmp_path / "tet.obj", POINTS, TRIANGLES, draco=True)
    assert draco.value.code == "unsupported"
    with pytest.raises(ValueError):
        tessera.write_mesh(tmp_path / "tet.obj", POINTS)


def sample_tags():
    """deploy/samples/cube.tags split by hand, as docs/FORMATS.md describes it."""
    creases, corners = [], []
    for line in (SAMPLES / "cube.tags").read_text().splitlines():
        words = line.split("#")[0].split()
        if not words:
            continue
        value = 10.0 if words[-1] == "inf" else float(words[-1])
        if words[0] == "crease":
            creases.append((int(words[1]), int(words[2]), value))
        else:
            corners.append((int(words[1]), value))
    return creases, corners


def test_read_tags_reads_the_sample(tmp_path):
    tags = tessera.read_tags(SAMPLES / "cube.tags")
    creases, corners = sample_tags()
    assert len(creases) == 12 and len(corners) == 1
    assert tags.creases.tolist() == [[a, b] for a, b, _ in creases]
    assert tags.crease_sharpness.tolist() == [s for _, _, s in creases]
    assert tags.corners.tolist() == [v for v, _ in corners]
    assert tags.corner_sharpness.tolist() == [s for _, s in corners]

    bad = tmp_path / "bad.tags"
    bad.write_text("crease 0 1 inf\ncrease 0 1 -2\n")
    with pytest.raises(tessera.Error) as refused:
        tessera.read_tags(bad)
    assert refused.value.code == "parse error"
    assert "bad.tags:2" in str(refused.value) and "-2" in str(refused.value)


def test_write_tags_writes_the_lines_of_the_format(tmp_path):
    tags = tessera.Tags(creases=[[0, 1], [1, 2]], crease_sharpness=[math.inf, 2.5], corners=[3],
                        corner_sharpness=[0.1])
    path = tmp_path / "t.tags"
    tessera.write_tags(path, tags)
    # float32(0.1)'s shortest decimal is 0.1; infinite sharpness is `inf`.
    assert path.read_text() == "crease 0 1 inf\ncrease 1 2 2.5\ncorner 3 0.1\n"
    back = tessera.read_tags(path)
    assert back.creases.tolist() == [[0, 1], [1, 2]]
    assert back.crease_sharpness.tolist() == [10.0, 2.5]
    assert back.corner_sharpness.tolist() == [float(np.float32(0.1))]

    # The sample, read and written, reads back to the same tags.
    sample = tessera.read_tags(SAMPLES / "cube.tags")
    tessera.write_tags(path, sample)
    again = tessera.read_tags(path)
    for name in ("creases", "crease_sharpness", "corners", "corner_sharpness"):
        assert np.array_equal(getattr(again, name), getattr(sample, name))


def test_written_tags_shape_the_surface(tmp_path):
    """Every edge of the tetrahedron infinitely sharp: each vertex meets three
    sharp edges and is a corner, which stays where it is, and every edge point
    is the edge's midpoint (the crease rules of Hoppe et al., "Piecewise
    Smooth Surface Reconstruction")."""
    edges = [[0, 1], [0, 2], [0, 3], [1, 2], [1, 3], [2, 3]]
    path = tmp_path / "sharp.tags"
    tessera.write_tags(path, tessera.Tags(creases=edges, crease_sharpness=[math.inf] * 6))
    level1 = tessera.refine(POINTS, TRIANGLES, level=1, tags=str(path))
    assert np.array_equal(level1.positions[:4], POINTS)
    midpoints = {tuple(np.round((POINTS[a] + POINTS[b]) / 2, 12)) for a, b in edges}
    assert {tuple(np.round(p, 12)) for p in level1.positions[4:]} == midpoints


def test_write_tags_refuses_what_the_reader_would_and_writes_nothing(tmp_path):
    path = tmp_path / "t.tags"
    cases = [
        (tessera.Tags(creases=[[0, 1], [1, 0]], crease_sharpness=[1, 2]), "tag 1 (crease 1 0): repeats tag 0"),
        (tessera.Tags(corners=[2, 2], corner_sharpness=[1, 1]), "repeats tag 0 (corner 2)"),
        (tessera.Tags(creases=[[4, 4]], crease_sharpness=[1]), "same vertex twice"),
        (tessera.Tags(corners=[-1], corner_sharpness=[1]), "0 or more"),
        (tessera.Tags(corners=[1], corner_sharpness=[-0.5]), "sharpness"),
        (tessera.Tags(corners=[1], corner_sharpness=[math.nan]), "sharpness"),
    ]
    for tags, reason in cases:
        with pytest.raises(tessera.Error) as refused:
            tessera.write_tags(path, tags)
        assert refused.value.code == "invalid argument" and reason in str(refused.value)
        assert not path.exists()
    with pytest.raises(ValueError):
        tessera.Tags(creases=[[0, 1]], crease_sharpness=[1, 2])
    with pytest.raises(ValueError):
        tessera.Tags(creases=[0, 1], crease_sharpness=[1])
    with pytest.raises(ValueError, match="integer"):
        tessera.Tags(corners=[1.5], corner_sharpness=[1])
    with pytest.raises(ValueError, match="out of range"):
        tessera.Tags(corners=[2**32 + 1], corner_sharpness=[1])


def all_edges_sharp():
    edges = [[0, 1], [0, 2], [0, 3], [1, 2], [1, 3], [2, 3]]
    return edges, tessera.Tags(creases=edges, crease_sharpness=[math.inf] * 6)


def assert_corners_kept_and_edges_halved(level1, edges):
    """Every vertex meets three sharp edges: a corner, kept; every edge point
    of a sharp edge is its midpoint (Hoppe et al.)."""
    assert np.array_equal(level1.positions[:4], POINTS)
    midpoints = {tuple(np.round((POINTS[a] + POINTS[b]) / 2, 12)) for a, b in edges}
    assert {tuple(np.round(p, 12)) for p in level1.positions[4:]} == midpoints


def test_a_cage_is_written_with_its_tags_to_obj_and_usda(tmp_path):
    edges, tags = all_edges_sharp()
    obj = tmp_path / "cage.obj"
    tessera.write_mesh(obj, POINTS, TRIANGLES, tags=tags, boundary="edge-and-corner", crease_method="chaikin")
    # OpenSubdiv's dialect (docs/FORMATS.md "Tags in OBJ"): `t NAME I/F/S values`.
    t_lines = [l[1:] for l in text_lines(obj) if l[0] == "t"]
    assert ["interpolateboundary", "1/0/0", "1"] in t_lines
    assert ["creasemethod", "0/0/1", "chaikin"] in t_lines
    creases = [l for l in t_lines if l[0] == "crease"]
    assert [[int(l[2]), int(l[3])] for l in creases] == edges
    assert all(l[1] == "2/1/0" and float(l[4]) == 10.0 for l in creases)
    assert_corners_kept_and_edges_halved(tessera.refine(str(obj), level=1), edges)

    usda = tmp_path / "cage.usda"
    tessera.write_mesh(usda, POINTS, TRIANGLES, tags=tags, scheme="loop")
    text = usda.read_text()
    assert 'subdivisionScheme = "loop"' in text and "creaseIndices" in text
    assert_corners_kept_and_edges_halved(tessera.refine(str(usda), level=1), edges)


def test_a_cage_refuses_what_its_readers_would(tmp_path):
    _, tags = all_edges_sharp()
    with pytest.raises(tessera.Error) as off:
        tessera.write_mesh(tmp_path / "c.off", POINTS, TRIANGLES, tags=tags)
    assert off.value.code == "unsupported"
    with pytest.raises(tessera.Error) as obj_scheme:
        tessera.write_mesh(tmp_path / "c.obj", POINTS, TRIANGLES, scheme="loop")
    assert obj_scheme.value.code == "invalid argument" and "OBJ states no scheme" in str(obj_scheme.value)
    with pytest.raises(tessera.Error) as usda_scheme:
        tessera.write_mesh(tmp_path / "c.usda", POINTS, TRIANGLES, tags=tags)
    assert "needs its scheme" in str(usda_scheme.value)
    diagonal = tessera.Tags(creases=[[0, 3]], crease_sharpness=[1.0])  # across the quad (0, 1, 3, 2)
    with pytest.raises(tessera.Error) as across:
        tessera.write_mesh(tmp_path / "c.obj", CUBE, QUADS, tags=diagonal)
    assert across.value.code == "invalid argument" and "no face has an edge" in str(across.value)
    missing = tessera.Tags(corners=[8], corner_sharpness=[1.0])
    with pytest.raises(tessera.Error) as vertex:
        tessera.write_mesh(tmp_path / "c.obj", CUBE, QUADS, tags=missing)
    assert "tag 0 (corner 8): the surface has 8 vertices" in str(vertex.value)
    assert not any(tmp_path.iterdir())
    with pytest.raises(ValueError, match="scheme must be"):
        tessera.write_mesh(tmp_path / "c.usda", POINTS, TRIANGLES, scheme="pentagonal")
