"""Documents as wholes: create (from a file and from arrays), list, open, export."""

import pathlib
import tempfile

import numpy as np
import pytest

import tessera
from conftest import SAMPLES


def test_create_from_a_file_then_list_and_open(session):
    ack = session.create_document(str(SAMPLES / "cube.obj"), name="listed cube", max_level=3)
    assert ack.document_id > 0
    assert ack.version == 1
    assert ack.scheme == "loop"  # the cube's faces are triangles
    listed = {d.document_id: d for d in session.list_documents()}
    assert ack.document_id in listed
    assert listed[ack.document_id].name == "listed cube"
    assert listed[ack.document_id].version == 1
    opened = session.open_document(ack.document_id)
    assert opened.document_id == ack.document_id
    assert opened.version == 0  # open's Ack carries no version (docs/PROTOCOL.md section 5)


def test_create_from_numpy_arrays(session):
    # A tetrahedron, faces counter-clockwise seen from outside.
    points = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=np.float64)
    faces = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]], dtype=np.int32)
    ack = session.create_document_from_arrays(points, faces, name="tetrahedron")
    assert ack.version == 1
    assert ack.scheme == "loop"
    names = {d.document_id: d.name for d in session.list_documents()}
    assert names[ack.document_id] == "tetrahedron"


def test_quads_from_arrays_make_a_catmull_clark_document(session):
    points = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], dtype=np.float64)
    ack = session.create_document_from_arrays(points, np.array([[0, 1, 2, 3]]), name="one quad")
    assert ack.scheme == "catmull-clark"


def test_a_mesh_the_server_cannot_import_is_rejected_with_its_reason(session):
    points = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], dtype=np.float64)
    faces = np.array([[0, 1, 1]])  # a repeated corner
    with pytest.raises(tessera.Rejected) as refused:
        session.create_document_from_arrays(points, faces, name="broken")
    assert refused.value.reason == "REJECT_REASON_INVALID_MESH"
    assert refused.value.message


def test_export_returns_a_glb(session, cube):
    with tempfile.TemporaryDirectory(prefix="tessera-python-export-") as d:
        out = pathlib.Path(d) / "cube.glb"
        version, glb = session.export_document(cube, 2, limit=True, path=str(out))
        assert out.read_bytes() == glb
    assert version == 1
    assert glb[:4] == b"glTF"  # the GLB magic (glTF 2.0 binary header)
    assert int.from_bytes(glb[4:8], "little") == 2  # container version 2
    assert int.from_bytes(glb[8:12], "little") == len(glb)


def test_the_base_cage_is_the_files_triangles(session, cube):
    version, sizes, vertices = session.cage(cube, 0)
    assert version == 1
    assert sizes.tolist() == [3] * 12
    # cube.obj's first two faces, `f 1 3 2` and `f 1 4 3`, as 0-based level-0 ids.
    assert vertices[:6].tolist() == [tessera.vertex_id(0, i) for i in (0, 2, 1, 0, 3, 2)]
    assert vertices.dtype == np.uint64
