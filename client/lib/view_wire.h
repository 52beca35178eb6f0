// A camera as a view-dependent subscription sends it (tessera.proto View,
// docs/PROTOCOL.md "Views"): the Subscribe that asks for one, and the
// SetView that moves it.
#pragma once

#include <cstdint>

#include "core/view/view.h"
#include "protocol/tessera.pb.h"

namespace tessera::client {

wire::View viewToWire(const View& view);
// `budget` 0: the server's limit (LodProfile.triangle_budget).
wire::ClientMessage subscribeWithView(uint64_t documentId, const View& view, uint64_t budget = 0);
wire::ClientMessage setView(uint64_t documentId, const View& view);

}  // namespace tessera::client
