// A subscriber's camera as the wire states it (tessera.proto View), made
// core's View and checked before any work (docs/VIEWS.md "The view"): a
// refusal names the field and the value, and costs the server nothing.
#pragma once

#include "core/util/status.h"
#include "core/view/view.h"
#include "protocol/tessera.pb.h"

namespace tessera::server {

// Errors (invalid argument): a number that is not finite, a degenerate
// direction or projection, a viewport or tolerance out of range.
Expected<View> viewFromWire(const wire::View& view);

}  // namespace tessera::server
