"""Work without a server: core's import and Loop refinement. Expected values
are Loop's rules worked by hand (Loop, "Smooth Subdivision Surfaces Based
on Triangles"), not computed by the code under test."""

import numpy as np
import pytest

import tessera
from conftest import SAMPLES

# A regular tetrahedron's corner at the origin and its three neighbours.
POINTS = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=np.float64)
FACES = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])


def test_read_mesh_returns_the_files_vertices_and_triangles():
    mesh = tessera.read_mesh(str(SAMPLES / "cube.obj"))
    assert mesh.positions.shape == (8, 3)
    assert mesh.triangles.shape == (12, 3)
    # cube.obj's `v` lines, in order.
    expected = [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]]
    assert np.array_equal(mesh.positions, np.array(expected, dtype=np.float64))


def test_refine_counts_and_loops_vertex_and_edge_rules():
    level1 = tessera.refine(POINTS, FACES, level=1)
    # V1 = V + E = 4 + 6, F1 = 4F.
    assert level1.positions.shape == (10, 3)
    assert level1.triangles.shape == (16, 3)
    # Vertex rule, valence 3 (beta = 3/16): 7/16 of the vertex, 3/16 of each neighbour.
    assert np.allclose(level1.positions[0], [3 / 16, 3 / 16, 3 / 16], atol=1e-12)
    # Every new vertex is an edge rule 3/8 (a + b) + 1/8 (c + d): on edge 0-1
    # (opposite 2 and 3) it is (3/8, 1/8, 1/8).
    assert any(np.allclose(p, [3 / 8, 1 / 8, 1 / 8], atol=1e-12) for p in level1.positions[4:])
    level2 = tessera.refine(POINTS, FACES, level=2)
    # V2 = V1 + E1 = 10 + (2 * 6 + 3 * 4), F2 = 64.
    assert level2.positions.shape == (34, 3)
    assert level2.triangles.shape == (64, 3)


def test_limit_positions_follow_loops_limit_mask():
    limit = tessera.refine(POINTS, FACES, level=0, limit=True)
    # Valence 3: chi = 1 / (3 / (8 beta) + n) = 1 / 5; the limit of the
    # origin is chi times the sum of its neighbours.
    assert np.allclose(limit.positions[0], [0.2, 0.2, 0.2], atol=1e-12)
    assert limit.normals.shape == (4, 3)
    assert np.allclose(np.linalg.norm(limit.normals, axis=1), 1.0)
    # The normal at the origin points away from the other corners.
    assert np.allclose(limit.normals[0], -np.ones(3) / np.sqrt(3), atol=1e-9)


def test_a_file_refines_like_its_arrays():
    from_file = tessera.refine(str(SAMPLES / "cube.obj"), level=2)
    mesh = tessera.read_mesh(str(SAMPLES / "cube.obj"))
    from_arrays = tessera.refine(mesh.positions, mesh.triangles, level=2)
    assert np.array_equal(from_file.positions, from_arrays.positions)
    assert np.array_equal(from_file.triangles, from_arrays.triangles)


def test_a_bad_mesh_raises_naming_the_problem():
    with pytest.raises(tessera.Error) as bad:
        tessera.refine(POINTS, np.array([[0, 1, 9]]), level=1)
    assert bad.value.code == "invalid mesh"


def test_ids_round_trip_between_text_and_packed():
    packed = tessera.vertex_id("v3:1234")
    assert packed == (3 << 58) | 1234  # docs/PROTOCOL.md 3.1: level in the top 6 bits
    assert tessera.format_vertex_id(packed) == "v3:1234"
    assert tessera.id_level(packed) == 3 and tessera.id_index(packed) == 1234
    assert tessera.edge_id("e1:5") == (1 << 58) | 5


# The unit cube as six quads, outward.
CUBE = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], dtype=np.float64)
QUADS = [[0, 1, 3, 2], [4, 6, 7, 5], [0, 4, 5, 1], [2, 3, 7, 6], [0, 2, 6, 4], [1, 5, 7, 3]]


def test_catmull_clark_follows_its_vertex_rule_and_keeps_quads():
    """Catmull & Clark's rules worked by hand: a corner of valence 3 goes to
    (F + 2E + (n - 3) V) / n, F the mean of its faces' centroids (1/3 each
    axis) and E of its edges' midpoints (1/6): 2/9 each axis."""
    level1 = tessera.refine(CUBE, QUADS, level=1, scheme="catmull-clark")
    assert level1.positions.shape == (8 + 12 + 6, 3)
    assert np.allclose(level1.positions[0], [2 / 9, 2 / 9, 2 / 9], atol=1e-12)
    offsets = np.asarray(level1.polygon_offsets)
    assert len(offsets) == 24 + 1 and np.all(np.diff(offsets) == 4)


def test_catmull_clark_limit_follows_its_limit_mask():
    """Halstead, Kass & DeRose, "Efficient, Fair Interpolation Using
    Catmull-Clark Surfaces": the limit of a vertex of valence n among quads
    weighs it n^2, its edge neighbours 4 and its faces' opposite corners 1,
    over n (n + 5). The cube's corner at the origin: (4 * 1 + 2) / 24 = 1/4."""
    limit = tessera.refine(CUBE, QUADS, level=0, limit=True, scheme="catmull-clark")
    assert np.allclose(limit.positions[0], [0.25, 0.25, 0.25], atol=1e-12)
    assert np.allclose(limit.normals[0], -np.ones(3) / np.sqrt(3), atol=1e-9)


def test_an_interpolating_scheme_keeps_the_base_vertices():
    level2 = tessera.refine(POINTS, FACES, level=2, scheme="butterfly")
    assert np.array_equal(level2.positions[:4], POINTS)
    assert level2.triangles.shape == (64, 3)


def test_a_scheme_refuses_what_it_cannot_do_as_value_errors():
    with pytest.raises(ValueError, match="limit"):
        tessera.refine(CUBE, QUADS, level=1, limit=True, scheme="bilinear")
    with pytest.raises(ValueError, match="no crease rules"):
        tessera.refine(POINTS, FACES, level=1, scheme="butterfly", crease_method="chaikin")
    with pytest.raises(ValueError, match="as they are"):
        tessera.refine(CUBE, QUADS, level=1, scheme="catmull-clark", triangulate=True)
    with pytest.raises(ValueError, match="pentagonal"):
        tessera.refine(POINTS, FACES, level=1, scheme="pentagonal")


def hexagonal_bipyramid():
    """Apex 0 of valence 6 (a regular vertex of Loop's scheme) over a ring
    of six points at uneven radii and heights, closed by apex 7 below."""
    angles = 2 * np.pi * np.arange(6) / 6
    radii = np.array([1.0, 1.3, 0.8, 1.1, 0.9, 1.2])
    heights = np.array([0.1, -0.2, 0.3, 0.0, 0.2, -0.1])
    ring = np.stack([radii * np.cos(angles), radii * np.sin(angles), heights], axis=1)
    points = np.vstack([[0.1, -0.05, 1.0], ring, [0.0, 0.0, -1.0]])
    top = [[0, 1 + i, 1 + (i + 1) % 6] for i in range(6)]  # counter-clockwise seen from above
    bottom = [[7, 1 + (i + 1) % 6, 1 + i] for i in range(6)]
    return points, np.array(top + bottom)


def test_limit_of_a_regular_vertex_follows_loops_masks():
    """Loop's limit masks at a vertex of valence 6, worked by hand: beta =
    (5/8 - (3/8 + cos(2 pi / 6) / 4)^2) / 6 = 1/16, chi = 1 / (3 / (8 beta) + 6)
    = 1/12, so the limit point is v / 2 + (sum of the ring) / 12; the tangents
    are sum cos(2 pi i / 6) p_i and sum sin(2 pi i / 6) p_i over the ring in
    order (Loop, "Smooth Subdivision Surfaces Based on Triangles"; Hoppe et
    al., "Piecewise Smooth Surface Reconstruction"), their cross product the
    normal of a counter-clockwise ring."""
    points, faces = hexagonal_bipyramid()
    ring = points[1:7]
    expected = points[0] / 2 + ring.sum(axis=0) / 12
    limit = tessera.refine(points, faces, level=0, limit=True)
    assert np.allclose(limit.positions[0], expected, atol=1e-12)
    angles = 2 * np.pi * np.arange(6) / 6
    t1 = (np.cos(angles)[:, None] * ring).sum(axis=0)
    t2 = (np.sin(angles)[:, None] * ring).sum(axis=0)
    normal = np.cross(t1, t2)
    assert np.allclose(limit.normals[0], normal / np.linalg.norm(normal), atol=1e-9)
    # A vertex's limit does not depend on the level it is evaluated from.
    level2 = tessera.refine(points, faces, level=2, limit=True)
    assert np.allclose(level2.positions[0], expected, atol=1e-12)
    assert np.allclose(level2.normals[0], limit.normals[0], atol=1e-9)


def test_limit_on_a_boundary_follows_the_crease_mask():
    """A boundary is an infinitely sharp crease (the default boundary rule,
    as OpenSubdiv's EDGE_ONLY): a vertex on it with two boundary neighbours
    goes to the limit of a cubic B-spline, (p_prev + 4 p + p_next) / 6
    (Hoppe et al., "Piecewise Smooth Surface Reconstruction")."""
    heights = np.array([0.0, 0.3, -0.2, 0.1, 0.5, 0.2, -0.1, 0.4, 0.0])
    points = np.array([[i + 0.1 * j, j, heights[i + 3 * j]] for j in range(3) for i in range(3)], dtype=float)
    faces = []
    for j in range(2):
        for i in range(2):
            a = i + 3 * j
            faces += [[a, a + 1, a + 4], [a, a + 4, a + 3]]
    limit = tessera.refine(points, np.array(faces), level=0, limit=True)
    # Vertex 1, on the bottom edge between vertices 0 and 2.
    assert np.allclose(limit.positions[1], (points[0] + 4 * points[1] + points[2]) / 6, atol=1e-12)
    assert np.allclose(tessera.refine(points, np.array(faces), level=2, limit=True).positions[1],
                       limit.positions[1], atol=1e-12)
