"""Morph documents (docs/PROTOCOL.md section 14): add_morph_key and
get_morph_control return their reply or raise tessera.Rejected with the
server's message, and subscribe(morph_t=) shows the surface between the
keys. Expected points are computed here with NumPy from the two keys' input
points (the control mesh at t is linear in t), and the surface at t = 1 is
checked by the affine invariance of subdivision: Loop's masks weigh points
with weights that sum to 1, so the surface of a scaled cage is the scaled
surface (Loop, "Smooth Subdivision Surfaces Based on Triangles")."""

import numpy as np
import pytest

import tessera
from conftest import SAMPLES

CENTRE = np.array([0.5, 0.5, 0.5])


def cube_keys():
    """deploy/samples/cube.obj's points and triangles, and a key 1 of the
    same triangles: the cube shrunk by half about its centre."""
    mesh = tessera.read_mesh(str(SAMPLES / "cube.obj"))
    return mesh.positions, mesh.triangles, CENTRE + 0.5 * (mesh.positions - CENTRE)


def test_a_document_with_one_key_refuses_the_morph_commands(session, cube):
    with pytest.raises(tessera.Rejected) as control:
        session.get_morph_control(cube, 0.5)
    assert control.value.reason == "REJECT_REASON_INVALID_ARGUMENT"
    assert "one key" in control.value.message
    with pytest.raises(tessera.Rejected) as subscribed:
        session.subscribe(cube, base_level=1, max_level=1, morph_t=0.5)
    assert subscribed.value.reason == "REJECT_REASON_INVALID_ARGUMENT"
    assert "has one key" in subscribed.value.message
    with pytest.raises(tessera.Rejected) as edit:
        session.move_vertex(cube, "v0:1", (1.0, 0.0, 0.1), key=1)
    assert edit.value.reason == "REJECT_REASON_NOT_FOUND"
    assert "key 1 does not exist" in edit.value.message


def test_a_key_of_another_connectivity_or_outside_the_grid_is_refused(session, cube):
    _, triangles, points1 = cube_keys()
    other = triangles.copy()
    # The bottom square (0, 1, 2, 3) cut along its other diagonal.
    assert other[0].tolist() == [0, 2, 1] and other[1].tolist() == [0, 3, 2]
    other[0], other[1] = [0, 3, 1], [1, 3, 2]
    with pytest.raises(tessera.Rejected) as refused:
        session.add_morph_key(cube, points1, other)
    assert refused.value.reason == "REJECT_REASON_INVALID_ARGUMENT"
    assert "triangle 0" in refused.value.message
    assert "one connectivity" in refused.value.message
    with pytest.raises(tessera.Rejected) as far:
        session.add_morph_key(cube, 100 * points1, triangles)
    assert far.value.reason == "REJECT_REASON_LIMIT_EXCEEDED"
    assert "outside the document's bounds" in far.value.message
    # Nothing was added: the document still has one key.
    with pytest.raises(tessera.Rejected):
        session.get_morph_control(cube, 0.5)


def test_the_control_points_at_t_lie_between_the_keys(session, cube):
    points0, triangles, points1 = cube_keys()
    ack = session.add_morph_key(cube, points1, triangles)
    assert ack.document_id == cube
    assert ack.version == 2  # created at 1: one journalled version

    control = session.get_morph_control(cube, 0.25, with_topology=True)
    assert control.document_id == cube and control.version == 2 and control.t == 0.25
    assert control.points.dtype == np.float32 and control.points.shape == (8, 3)
    expected = 0.75 * points0 + 0.25 * points1
    assert np.allclose(control.points, expected, atol=1e-6)
    assert np.array_equal(control.triangles, triangles)
    assert control.creases.shape == (0, 2)  # cube.obj without tags
    assert np.array_equal(control.vertex_sharpness, np.zeros(8, dtype=np.float32))
    assert control.max_level == 4
    assert (control.crease_method, control.boundary) == ("uniform", "edge-only")
    assert control.image_from == b"" and control.image_to == b""

    plain = session.get_morph_control(cube, 1.0)
    assert plain.triangles is None and plain.crease_method == ""
    assert np.allclose(plain.points, points1, atol=1e-6)

    with pytest.raises(tessera.Rejected) as again:
        session.add_morph_key(cube, points1, triangles)
    assert again.value.reason == "REJECT_REASON_INVALID_ARGUMENT"
    assert "already has two keys" in again.value.message
    with pytest.raises(tessera.Rejected) as outside:
        session.get_morph_control(cube, 1.5)
    assert outside.value.reason == "REJECT_REASON_INVALID_ARGUMENT"
    assert "not in [0, 1]" in outside.value.message


def test_a_subscription_at_t_shows_the_morph_and_edits_name_their_key(session, cube):
    _, triangles, points1 = cube_keys()
    session.subscribe(cube, base_level=2, max_level=2)
    key0 = session.wait_for(cube, version=1, timeout=30).positions()
    added = session.add_morph_key(cube, points1, triangles)

    with pytest.raises(tessera.Rejected) as outside:
        session.subscribe(cube, base_level=2, max_level=2, morph_t=1.5)
    assert outside.value.reason == "REJECT_REASON_INVALID_ARGUMENT"
    ack = session.subscribe(cube, base_level=2, max_level=2, morph_t=1.0)
    assert ack.version == added.version
    at1 = session.wait_for(cube, version=added.version, timeout=30).positions()
    assert at1.shape == key0.shape
    # Affine invariance: the surface of key 1 is key 0's, shrunk by half.
    # Regions are quantized on the document's grid: a tolerance of 1e-3.
    assert np.allclose(at1.min(axis=0), CENTRE + 0.5 * (key0.min(axis=0) - CENTRE), atol=1e-3)
    assert np.allclose(at1.max(axis=0), CENTRE + 0.5 * (key0.max(axis=0) - CENTRE), atol=1e-3)

    # An edit of key 1 moves the surface at t = 1 past key 1's old extent.
    moved = session.move_vertex(cube, "v0:6", (0.9, 0.9, 0.9), key=1)
    assert moved.version == added.version + 1 and moved.edit_id > 0
    after = session.wait_for(cube, version=moved.version, timeout=30).positions()
    assert after.max() > at1.max() + 0.05
    with pytest.raises(tessera.Rejected) as no_key:
        session.move_vertex(cube, "v0:6", (0.9, 0.9, 0.9), key=2)
    assert no_key.value.reason == "REJECT_REASON_NOT_FOUND"


def test_a_2d_morph_sends_its_key_and_images_from_files(session):
    folder = SAMPLES / "morph"
    doc = session.create_document(str(folder / "mesh_a.obj"), name="morph").document_id
    session.open_document(doc)
    with pytest.raises(ValueError, match="both images or neither"):
        session.add_morph_key(doc, str(folder / "mesh_b.obj"), image_from=str(folder / "a.png"))
    session.add_morph_key(doc, folder / "mesh_b.obj", image_from=str(folder / "a.png"),
                          image_to=str(folder / "b.png"))
    control = session.get_morph_control(doc, 0.5, with_topology=True)
    assert control.image_from == (folder / "a.png").read_bytes()
    assert control.image_to == (folder / "b.png").read_bytes()
    a = tessera.read_mesh(str(folder / "mesh_a.obj")).positions
    b = tessera.read_mesh(str(folder / "mesh_b.obj")).positions
    # Pixel coordinates (up to a few hundred) as float32: a relative tolerance.
    assert np.allclose(control.points, 0.5 * (a + b), rtol=1e-6, atol=1e-4)
