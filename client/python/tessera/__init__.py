"""Tessera for Python: tessera-server sessions and offline work (refinement,
limit surfaces, mesh and tag files).

Everything here is Tessera's C++ client library and core, compiled into
``tessera._tessera`` (docs/PYTHON.md). Sessions speak the protocol of
docs/PROTOCOL.md through ``client::Session``; regions arrive decoded by
``client::DocumentView`` as NumPy arrays.

    import tessera
    with tessera.Session.connect("127.0.0.1", 7878, token) as s:
        doc = s.create_document("cube.obj").document_id
        s.open_document(doc)
        ack = s.move_vertex(doc, "v0:3", (0.0, 0.0, 1.5))
        print(ack.version, ack.edit_id)

Errors are ``tessera.Error`` and its subclasses: ``Rejected`` (a command the
server refused, with its reason), ``ServerError`` and
``AuthenticationFailed`` (the server's Error), ``Timeout``.
"""

from tessera._tessera import (
    Ack,
    AuthenticationFailed,
    DocumentInfo,
    DocumentView,
    Error,
    Mesh,
    MorphControl,
    Participant,
    Region,
    Rejected,
    ServerError,
    Session,
    Tags,
    Timeout,
    edge_id,
    format_vertex_id,
    id_index,
    id_level,
    read_mesh,
    read_tags,
    refine,
    vertex_id,
    write_mesh,
    write_tags,
)

__all__ = [
    "Ack",
    "AuthenticationFailed",
    "DocumentInfo",
    "DocumentView",
    "Error",
    "Mesh",
    "MorphControl",
    "Participant",
    "Region",
    "Rejected",
    "ServerError",
    "Session",
    "Tags",
    "Timeout",
    "edge_id",
    "format_vertex_id",
    "id_index",
    "id_level",
    "read_mesh",
    "read_tags",
    "refine",
    "vertex_id",
    "write_mesh",
    "write_tags",
]
