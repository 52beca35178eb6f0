"""The POSITION array of a GLB's first primitive.

The add-on asks the server for a document's level-0 control points with
`Session.export_document(doc, 0)` (docs/PYTHON.md), which returns the GLB
that `tessera remote export` writes: one mesh, one primitive, the level's
vertices first in the document's order (vertex i is `v0:i`), then copies
of vertices split along sharp features, for their normals.
"""

import json
import struct

import numpy as np

GLB_MAGIC = 0x46546C67  # "glTF"
FLOAT = 5126


def glb_positions(glb):
    """(N, 3) float64 positions of the first primitive of a GLB (bytes)."""
    if len(glb) < 20:
        raise ValueError(f"GLB of {len(glb)} bytes is too short")
    magic, _version, _length = struct.unpack_from("<III", glb, 0)
    if magic != GLB_MAGIC:
        raise ValueError("not a GLB (bad magic)")
    json_length, _json_type = struct.unpack_from("<II", glb, 12)
    document = json.loads(glb[20:20 + json_length])
    bin_start = 20 + json_length
    bin_length, _bin_type = struct.unpack_from("<II", glb, bin_start)
    binary = glb[bin_start + 8:bin_start + 8 + bin_length]
    primitive = document["meshes"][0]["primitives"][0]
    accessor = document["accessors"][primitive["attributes"]["POSITION"]]
    if accessor["componentType"] != FLOAT or accessor["type"] != "VEC3":
        raise ValueError("GLB positions are not float VEC3 (a Draco GLB is not read here)")
    view = document["bufferViews"][accessor["bufferView"]]
    offset = view.get("byteOffset", 0) + accessor.get("byteOffset", 0)
    stride = view.get("byteStride", 12)
    count = accessor["count"]
    raw = np.frombuffer(binary, dtype=np.uint8, count=stride * (count - 1) + 12 if count else 0,
                        offset=offset)
    floats = np.lib.stride_tricks.as_strided(raw.view(np.uint8), shape=(count, 12), strides=(stride, 1))
    return np.ascontiguousarray(floats).view("<f4").reshape(count, 3).astype(np.float64)
