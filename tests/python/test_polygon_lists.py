"""create_document_from_arrays with faces as a list of index lists of mixed
lengths (docs/PYTHON.md "Documents"), as the Blender add-on sends a mesh of
quads and triangles."""

import numpy as np


def test_mixed_polygon_lists_make_a_catmull_clark_document(session):
    points = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0.5, 0.5, 1]], float)
    faces = [[0, 3, 2, 1], [0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]]
    ack = session.create_document_from_arrays(points, faces, name="pyramid", max_level=2)
    assert ack.scheme == "catmull-clark"
    session.open_document(ack.document_id)
    _, sizes, corners = session.cage(ack.document_id, 0)
    assert sizes.tolist() == [4, 3, 3, 3, 3]
    assert corners.tolist() == [0, 3, 2, 1, 0, 1, 4, 1, 2, 4, 2, 3, 4, 3, 0, 4]
