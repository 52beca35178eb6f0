"""Edit commands: each returns its Ack or raises tessera.Rejected with the
server's reason (docs/PROTOCOL.md sections 5, 8.1, 13.1)."""

import pytest

import tessera
from conftest import SAMPLES


def test_move_vertex_returns_the_ack(session, cube):
    ack = session.move_vertex(cube, "v0:3", (0.1, 1.2, -0.1))
    assert ack.document_id == cube
    assert ack.version == 2  # created at 1, this is the first edit
    assert ack.edit_id > 0
    packed = session.offset_vertices(cube, [tessera.vertex_id(1, 2)], (0.0, 0.05, 0.0))
    assert packed.version == 3
    assert packed.edit_id != ack.edit_id


def test_undo_and_redo_name_the_edit(session, cube):
    move = session.move_vertex(cube, tessera.vertex_id("v0:6"), (1.1, 1.1, 1.1))
    undone = session.undo(cube, move.edit_id)
    assert undone.edit_id == move.edit_id
    assert undone.version == move.version + 1
    with pytest.raises(tessera.Rejected) as again:
        session.undo(cube, move.edit_id)
    assert again.value.reason == "REJECT_REASON_INVALID_STATE"
    redone = session.redo(cube, move.edit_id)
    assert redone.edit_id == move.edit_id
    assert redone.version == move.version + 2


def test_sharpness_commands(session, cube):
    crease = session.set_edge_sharpness(cube, "e0:0", float("inf"))
    corner = session.set_vertex_sharpness(cube, "v0:0", 2.0)
    assert corner.version == crease.version + 1
    typed = session.set_vertex_type(cube, "v0:6", "cusp")
    assert typed.version == corner.version + 1
    with pytest.raises(ValueError):
        session.set_vertex_type(cube, "v0:6", "pointy")


def test_an_unknown_vertex_is_rejected_with_reason_and_message(session, cube):
    with pytest.raises(tessera.Rejected) as refused:
        session.move_vertex(cube, "v0:999", (0.0, 0.0, 0.0))
    assert refused.value.reason == "REJECT_REASON_NOT_FOUND"
    assert refused.value.reason_code == 2  # tessera.proto RejectReason
    assert "v0:999" in refused.value.message
    # The connection stays usable after a Reject.
    assert session.move_vertex(cube, "v0:1", (1.05, 0.0, 0.0)).version == 2


def test_a_document_not_open_is_rejected(session):
    doc = session.create_document(str(SAMPLES / "cube.obj")).document_id
    with pytest.raises(tessera.Rejected) as refused:
        session.move_vertex(doc, "v0:1", (1.0, 0.0, 0.1))
    assert refused.value.reason == "REJECT_REASON_NOT_OPEN"


def test_an_edit_script_is_one_batch(session, cube):
    ack = session.edit(cube, "move v0:2 to 1.1 1.1 0\noffset v1:9 by 0 0 0.1\ncrease e0:3 inf\n")
    assert ack.version == 2  # one version for the whole batch
    assert len(ack.edit_ids) == 3
    assert ack.edit_id == ack.edit_ids[-1]


def test_a_refused_command_refuses_the_batch_and_names_it(session, cube):
    with pytest.raises(tessera.Rejected) as refused:
        session.edit(cube, "move v0:2 to 1.1 1.1 0\nmove v0:999 to 0 0 0\n")
    assert refused.value.reason == "REJECT_REASON_NOT_FOUND"
    assert refused.value.batch_index == 2
    # Nothing of it was applied: the next edit is still version 2.
    assert session.move_vertex(cube, "v0:2", (1.1, 1.1, 0.0)).version == 2


def test_a_script_that_does_not_parse_raises_before_sending(session, cube):
    with pytest.raises(tessera.Error) as bad:
        session.edit(cube, "move v0:2 somewhere\n")
    assert "script:1" in str(bad.value)


def test_an_edge_named_by_its_ends_is_the_edge_the_numbering_gives(session):
    """docs/PROTOCOL.md 3.2: base edges are numbered by a scan of the
    triangles in order, so e0:0 joins the first triangle's first two corners:
    cube.obj's first face is 'f 1 3 2', vertices 0 and 2. Tagging those ends
    must give the surface tagging e0:0 gives, and another edge another."""
    def tagged(edge):
        doc = session.create_document(str(SAMPLES / "cube.obj"), max_level=2).document_id
        session.open_document(doc)
        session.set_edge_sharpness(doc, edge, float("inf"))
        return session.export_document(doc, 2, limit=True)[1]

    by_id = tagged("e0:0")
    assert tagged(("v0:2", "v0:0")) == by_id  # either order
    assert tagged([tessera.vertex_id("v0:0"), tessera.vertex_id("v0:2")]) == by_id
    assert tagged(("v0:2", "v0:1")) != by_id  # e0:1, the triangle's second edge


def test_an_edge_named_by_ends_that_no_edge_joins_is_refused(session, cube):
    # cube.obj: vertices 0 and 6 are opposite corners of the cube.
    with pytest.raises(tessera.Rejected) as refused:
        session.set_edge_sharpness(cube, ("v0:0", "v0:6"), 2.0)
    assert refused.value.reason == "REJECT_REASON_INVALID_ARGUMENT"
    with pytest.raises(ValueError):
        session.set_edge_sharpness(cube, ("v0:0", "v0:1", "v0:2"), 2.0)
