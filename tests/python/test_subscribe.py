"""Subscriptions: the snapshot and deltas decoded by client::DocumentView,
read as NumPy arrays (docs/PROTOCOL.md section 6)."""

import time

import numpy as np

import tessera
from conftest import ADMIN_TOKEN

# Regions carry positions quantized on the document's grid (docs/REGION_ENCODING.md):
# far finer than this for a unit cube.
QUANTIZATION = 1e-3


def test_regions_as_arrays(session, cube):
    ack = session.subscribe(cube, base_level=1, max_level=2)
    assert ack.version == 1
    view = session.wait_for(cube, version=ack.version, timeout=30)
    assert view.ready and view.version == 1

    positions, triangles, ids = view.positions(), view.triangles(), view.vertex_ids()
    assert positions.dtype == np.float64 and positions.shape[1] == 3
    assert triangles.dtype == np.int32 and triangles.shape[1] == 3
    assert ids.dtype == np.uint64 and ids.shape == (positions.shape[0],)
    assert triangles.min() >= 0 and triangles.max() < positions.shape[0]
    # Level 1 at least everywhere: the cube's 12 triangles, each split in 4.
    assert triangles.shape[0] >= 48
    assert view.triangle_count == triangles.shape[0]
    # Every base vertex is displayed; it arrives with its birth-level id v0:i.
    for i in range(8):
        assert tessera.vertex_id(0, i) in set(ids.tolist())
    # The limit surface of the unit cube lies inside it.
    assert positions.min() > -1e-9 and positions.max() < 1 + 1e-9

    regions = view.regions()
    assert len(regions) > 0
    assert sum(r.triangles.shape[0] for r in regions.values()) == triangles.shape[0]
    view.verify()  # the server's surface hash matches what was decoded

    surface = view.surface()
    assert surface.positions.shape[1] == 3
    assert surface.triangles.shape[0] == triangles.shape[0]


def test_a_moved_vertex_arrives_in_a_delta(session, cube):
    ack = session.subscribe(cube, base_level=1, max_level=2)
    session.wait_for(cube, version=ack.version, timeout=30)
    target = np.array([0.1, 1.2, -0.1])
    moved = session.move_vertex(cube, "v0:3", tuple(target))
    view = session.wait_for(cube, version=moved.version, timeout=30)
    assert view.version == moved.version

    ids, positions = view.vertex_ids(), view.positions()
    rows = np.nonzero(ids == tessera.vertex_id("v0:3"))[0]
    assert rows.size > 0, "the moved vertex is among the regions' ids"
    # Direct manipulation puts the vertex's limit position on the target.
    for row in rows:
        assert np.allclose(positions[row], target, atol=QUANTIZATION)
    view.verify()

    # An id picked from the arrays (a NumPy uint64) names the vertex in the next edit.
    picked = ids[rows[0]]
    assert isinstance(picked, np.uint64)
    again = session.move_vertex(cube, picked, (0.1, 1.25, -0.1))
    assert again.version == moved.version + 1
    assert session.offset_vertices(cube, ids[rows[:1]], (0.0, 0.0, 0.01)).version == moved.version + 2


def test_presence_lists_both_participants(server, session, cube):
    with tessera.Session.connect("127.0.0.1", server.port, ADMIN_TOKEN, name="bob", timeout=20) as bob:
        bob.open_document(cube)
        bob.select(cube, ["v0:5"])
        deadline = time.monotonic() + 10
        seen = {}
        while time.monotonic() < deadline:
            session.receive(timeout=0.2)
            seen = {p.name: p for p in session.participants(cube)}
            if "bob" in seen and seen["bob"].selected_vertex_ids:
                break
        assert set(seen) == {"pytest", "bob"}
        assert seen["bob"].session_id == bob.session_id
        assert seen["bob"].selected_vertex_ids == [tessera.vertex_id(0, 5)]
        assert seen["pytest"].role == "admin"


def test_waiting_for_a_version_that_never_comes_times_out(session, cube):
    ack = session.subscribe(cube, base_level=1, max_level=1)
    session.wait_for(cube, version=ack.version, timeout=30)
    started = time.monotonic()
    try:
        session.wait_for(cube, version=ack.version + 5, timeout=0.5)
    except tessera.Timeout as e:
        assert "no version" in str(e)
    else:
        raise AssertionError("wait_for returned without the version")
    assert time.monotonic() - started < 5


def test_a_view_dependent_subscription_completes_its_view(session, cube):
    # The unit cube seen from in front of its z = 1 face.
    ack = session.subscribe_view(cube, eye=(0.5, 0.5, 3.0), forward=(0.0, 0.0, -1.0), width=640, height=480)
    assert ack.document_id == cube
    deadline = time.monotonic() + 30
    view = session.view(cube)
    while not view.view_complete and time.monotonic() < deadline:
        session.receive(timeout=0.5)
    assert view.view_complete
    assert view.triangles().shape[0] > 0
    positions = view.positions()
    assert positions.min() > -1e-9 and positions.max() < 1 + 1e-9
