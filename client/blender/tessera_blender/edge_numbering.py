"""Tessera's numbers of the base mesh's edges.

Level 0's edges are numbered in order of first use by a scan of the faces
in order, face (c0, c1, ..., cn-1) visiting (c0, c1), (c1, c2), ...,
(cn-1, c0) (docs/PROTOCOL.md section 3.2, "Level 0";
core/topology/level_builder.h). The add-on sends a crease edit as
`crease e0:K S`, so it needs K for the edge Blender knows by its two ends.
"""


def edge_numbers(faces):
    """A dict from an edge's ends (lower index first) to its level-0 number."""
    numbers = {}
    for face in faces:
        n = len(face)
        for j in range(n):
            a, b = int(face[j]), int(face[(j + 1) % n])
            key = (a, b) if a < b else (b, a)
            if key not in numbers:
                numbers[key] = len(numbers)
    return numbers
