# Type stub of the tessera package (docs/PYTHON.md): the classes and
# functions of the compiled tessera._tessera, which __init__.py re-exports.
import os
from types import TracebackType
from typing import Iterable, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

# A vertex or edge: its packed 64-bit id, or its text ("v2:40", "e1:5").
ElementId = Union[int, str]
VertexIds = Union[ElementId, Iterable[ElementId], npt.NDArray[np.uint64]]
Vec3 = Tuple[float, float, float]
PathLike = Union[str, "os.PathLike[str]"]

class Error(RuntimeError):
    code: str

class Timeout(Error): ...

class Rejected(Error):
    reason: str
    reason_code: int
    message: str
    batch_index: int

class ServerError(Error):
    code: str
    error_code: int
    fatal: bool

class AuthenticationFailed(ServerError): ...

class Ack:
    @property
    def document_id(self) -> int: ...
    @property
    def version(self) -> int: ...
    @property
    def edit_id(self) -> int: ...
    @property
    def edit_ids(self) -> list[int]: ...
    @property
    def dropped_vertices(self) -> int: ...
    @property
    def creased_edges(self) -> int: ...
    @property
    def scheme(self) -> str: ...

class DocumentInfo:
    @property
    def document_id(self) -> int: ...
    @property
    def name(self) -> str: ...
    @property
    def version(self) -> int: ...
    @property
    def max_level(self) -> int: ...

class Participant:
    @property
    def session_id(self) -> int: ...
    @property
    def name(self) -> str: ...
    @property
    def role(self) -> str: ...
    @property
    def selected_vertex_ids(self) -> list[int]: ...

class Mesh:
    @property
    def positions(self) -> npt.NDArray[np.float64]: ...
    @property
    def normals(self) -> Optional[npt.NDArray[np.float64]]: ...
    @property
    def triangles(self) -> npt.NDArray[np.int32]: ...
    @property
    def polygon_offsets(self) -> Optional[npt.NDArray[np.int32]]: ...
    @property
    def polygon_corners(self) -> Optional[npt.NDArray[np.int32]]: ...

class MorphControl:
    @property
    def document_id(self) -> int: ...
    @property
    def version(self) -> int: ...
    @property
    def t(self) -> float: ...
    @property
    def points(self) -> npt.NDArray[np.float32]: ...
    @property
    def triangles(self) -> Optional[npt.NDArray[np.uint32]]: ...
    @property
    def creases(self) -> Optional[npt.NDArray[np.uint32]]: ...
    @property
    def crease_sharpness(self) -> Optional[npt.NDArray[np.float32]]: ...
    @property
    def vertex_sharpness(self) -> Optional[npt.NDArray[np.float32]]: ...
    @property
    def crease_method(self) -> str: ...
    @property
    def boundary(self) -> str: ...
    @property
    def max_level(self) -> int: ...
    @property
    def image_from(self) -> bytes: ...
    @property
    def image_to(self) -> bytes: ...

class Tags:
    def __init__(
        self,
        *,
        creases: Optional[npt.ArrayLike] = None,
        crease_sharpness: Optional[npt.ArrayLike] = None,
        corners: Optional[npt.ArrayLike] = None,
        corner_sharpness: Optional[npt.ArrayLike] = None,
    ) -> None: ...
    @property
    def creases(self) -> npt.NDArray[np.int32]: ...
    @property
    def crease_sharpness(self) -> npt.NDArray[np.float64]: ...
    @property
    def corners(self) -> npt.NDArray[np.int32]: ...
    @property
    def corner_sharpness(self) -> npt.NDArray[np.float64]: ...

class Region:
    @property
    def region_id(self) -> int: ...
    @property
    def positions(self) -> npt.NDArray[np.float64]: ...
    @property
    def normals(self) -> npt.NDArray[np.float64]: ...
    @property
    def triangles(self) -> npt.NDArray[np.int32]: ...
    @property
    def vertex_ids(self) -> npt.NDArray[np.uint64]: ...

class DocumentView:
    @property
    def document_id(self) -> int: ...
    @property
    def version(self) -> int: ...
    @property
    def ready(self) -> bool: ...
    @property
    def needs_resync(self) -> bool: ...
    @property
    def triangle_count(self) -> int: ...
    @property
    def view_complete(self) -> bool: ...
    @property
    def bytes_received(self) -> int: ...
    @property
    def announced_surface_hash(self) -> int: ...
    def regions(self) -> dict[int, Region]: ...
    def positions(self) -> npt.NDArray[np.float64]: ...
    def vertex_ids(self) -> npt.NDArray[np.uint64]: ...
    def normals(self) -> npt.NDArray[np.float64]: ...
    def triangles(self) -> npt.NDArray[np.int32]: ...
    def surface(self) -> Mesh: ...
    def surface_hash(self) -> int: ...
    def verify(self) -> None: ...

class Session:
    @staticmethod
    def connect(
        host: str = "127.0.0.1",
        port: int = 7878,
        token: str = "",
        name: str = "tessera-python",
        *,
        tls: bool = False,
        tls_ca_file: str = "",
        timeout: float = 10.0,
    ) -> Session: ...
    @property
    def session_id(self) -> int: ...
    @property
    def role(self) -> str: ...
    @property
    def timeout(self) -> float: ...
    @property
    def closed(self) -> bool: ...
    def close(self) -> None: ...
    def __enter__(self) -> Session: ...
    def __exit__(
        self,
        exc_type: Optional[type[BaseException]],
        exc: Optional[BaseException],
        tb: Optional[TracebackType],
    ) -> None: ...
    def ping(self, timeout: Optional[float] = None) -> int: ...
    def stats(self, timeout: Optional[float] = None) -> dict[str, float]: ...
    def receive(self, timeout: float = 1.0) -> Optional[dict[str, object]]: ...
    def participants(self, document_id: int) -> list[Participant]: ...
    def select(self, document_id: int, vertex_ids: VertexIds) -> None: ...
    # Documents
    def list_documents(self, timeout: Optional[float] = None) -> list[DocumentInfo]: ...
    def create_document(
        self,
        path: str,
        *,
        name: Optional[str] = None,
        tags: Optional[str] = None,
        max_level: int = 0,
        triangulate: bool = False,
        drop_unused: bool = False,
        crease_angle: Optional[float] = None,
        scheme: Optional[str] = None,
        crease_method: Optional[str] = None,
        boundary: Optional[str] = None,
        timeout: Optional[float] = None,
    ) -> Ack: ...
    def create_document_from_arrays(
        self,
        points: npt.ArrayLike,
        faces: Union[npt.ArrayLike, Sequence[Sequence[int]]],
        *,
        name: str = "arrays",
        tags: Optional[str] = None,
        max_level: int = 0,
        scheme: Optional[str] = None,
        crease_method: Optional[str] = None,
        boundary: Optional[str] = None,
        timeout: Optional[float] = None,
    ) -> Ack: ...
    def open_document(self, document_id: int, timeout: Optional[float] = None) -> Ack: ...
    def close_document(self, document_id: int, timeout: Optional[float] = None) -> Ack: ...
    def delete_document(self, document_id: int, timeout: Optional[float] = None) -> Ack: ...
    def export_document(
        self,
        document_id: int,
        level: int,
        *,
        limit: bool = False,
        draco: bool = False,
        path: Optional[str] = None,
        timeout: Optional[float] = None,
    ) -> Tuple[int, bytes]: ...
    def cage(
        self, document_id: int, level: int = 0, timeout: Optional[float] = None
    ) -> Tuple[int, npt.NDArray[np.uint32], npt.NDArray[np.uint64]]: ...
    def grant_token(
        self, token: str, role: str, document_id: int = 0, timeout: Optional[float] = None
    ) -> Ack: ...
    # Edits
    def move_vertex(
        self, document_id: int, vertex_ids: VertexIds, target: Vec3, *, key: int = 0,
        timeout: Optional[float] = None
    ) -> Ack: ...
    def offset_vertices(
        self, document_id: int, vertex_ids: VertexIds, displacement: Vec3, *, key: int = 0,
        timeout: Optional[float] = None
    ) -> Ack: ...
    def set_edge_sharpness(
        self, document_id: int, edge_id: Union[ElementId, Tuple[ElementId, ElementId]], sharpness: float, *,
        key: int = 0,
        timeout: Optional[float] = None
    ) -> Ack: ...
    def set_vertex_sharpness(
        self, document_id: int, vertex_id: ElementId, sharpness: float, *, key: int = 0,
        timeout: Optional[float] = None
    ) -> Ack: ...
    def set_vertex_type(
        self, document_id: int, vertex_id: ElementId, type: str, *, key: int = 0,
        timeout: Optional[float] = None
    ) -> Ack: ...
    def set_interpolation(
        self, document_id: int, vertex_id: ElementId, interpolating: bool = True, *,
        tension: float = 1.0, tangent: Optional[Vec3] = None, key: int = 0,
        timeout: Optional[float] = None
    ) -> Ack: ...
    def undo(self, document_id: int, edit_id: int, *, key: int = 0, timeout: Optional[float] = None) -> Ack: ...
    def redo(self, document_id: int, edit_id: int, *, key: int = 0, timeout: Optional[float] = None) -> Ack: ...
    def edit(self, document_id: int, script: str, *, key: int = 0, timeout: Optional[float] = None) -> Ack: ...
    # Morph documents
    def add_morph_key(
        self,
        document_id: int,
        source: Union[PathLike, npt.ArrayLike],
        faces: Optional[Union[npt.ArrayLike, Sequence[Sequence[int]]]] = None,
        *,
        image_from: Optional[str] = None,
        image_to: Optional[str] = None,
        timeout: Optional[float] = None,
    ) -> Ack: ...
    def get_morph_control(
        self, document_id: int, t: float, *, with_topology: bool = False, timeout: Optional[float] = None
    ) -> MorphControl: ...
    # Subscriptions
    def subscribe(
        self,
        document_id: int,
        *,
        base_level: int = 2,
        max_level: int = 5,
        angle_threshold: float = 10.0,
        triangle_budget: int = 0,
        fidelity: int = 0,
        vertex_ids: bool = True,
        with_commands: bool = False,
        morph_t: Optional[float] = None,
        timeout: Optional[float] = None,
    ) -> Ack: ...
    def subscribe_view(
        self,
        document_id: int,
        *,
        eye: Vec3,
        forward: Vec3,
        up: Vec3 = (0.0, 1.0, 0.0),
        width: int,
        height: int,
        fov_y: float = 0.8,
        ortho_height: Optional[float] = None,
        near: float = 1e-3,
        tolerance: float = 1.0,
        triangle_budget: int = 0,
        timeout: Optional[float] = None,
    ) -> Ack: ...
    def set_view(
        self,
        document_id: int,
        *,
        eye: Vec3,
        forward: Vec3,
        up: Vec3 = (0.0, 1.0, 0.0),
        width: int,
        height: int,
        fov_y: float = 0.8,
        ortho_height: Optional[float] = None,
        near: float = 1e-3,
        tolerance: float = 1.0,
    ) -> None: ...
    def unsubscribe(self, document_id: int, timeout: Optional[float] = None) -> Ack: ...
    def view(self, document_id: int) -> Optional[DocumentView]: ...
    def wait_for(
        self, document_id: int, version: Optional[int] = None, timeout: float = 10.0
    ) -> DocumentView: ...

def vertex_id(text_or_level: Union[str, int], index: Optional[int] = None) -> int: ...
def edge_id(text_or_level: Union[str, int], index: Optional[int] = None) -> int: ...
def format_vertex_id(packed: int) -> str: ...
def id_level(packed: int) -> int: ...
def id_index(packed: int) -> int: ...
def read_mesh(
    source: Union[PathLike, npt.ArrayLike],
    faces: Optional[npt.ArrayLike] = None,
    *,
    tags: Optional[str] = None,
    triangulate: bool = False,
    drop_unused: bool = False,
    crease_angle: Optional[float] = None,
) -> Mesh: ...
def refine(
    source: Union[PathLike, npt.ArrayLike],
    faces: Optional[npt.ArrayLike] = None,
    *,
    level: int,
    limit: bool = False,
    tags: Optional[str] = None,
    triangulate: bool = False,
    drop_unused: bool = False,
    crease_angle: Optional[float] = None,
    crease_method: str = "uniform",
    boundary: str = "edge-only",
    scheme: str = "loop",
) -> Mesh: ...
def write_mesh(
    path: PathLike,
    source: Union[Mesh, npt.ArrayLike],
    faces: Optional[Union[npt.ArrayLike, Sequence[Sequence[int]]]] = None,
    *,
    normals: Optional[npt.ArrayLike] = None,
    draco: bool = False,
    tags: Optional[Tags] = None,
    scheme: Optional[str] = None,
    boundary: Optional[str] = None,
    crease_method: Optional[str] = None,
) -> None: ...
def read_tags(path: PathLike) -> Tags: ...
def write_tags(path: PathLike, tags: Tags) -> None: ...
