// Packed ids with a special meaning on the wire (docs/PROTOCOL.md 7.2).
#pragma once

#include <cstdint>

namespace tessera {

// SetEdgeSharpness.edge_id when the edge is named by end_vertex_ids instead:
// all ones (level 63), which a server without end_vertex_ids refuses as an
// unknown edge rather than tagging e0:0, the proto3 default.
inline constexpr uint64_t kEdgeIdNamedByEnds = ~uint64_t{0};

}  // namespace tessera
