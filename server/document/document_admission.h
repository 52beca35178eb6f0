// Admission of a document's work (docs/ARCHITECTURE.md, "Bulk work"): the
// triangle estimates a request is judged by before any work, and the lane of
// the document's serial queue (server/base/serial_queue.h) a task takes.
// Estimates come from the document's level counts alone, so a request over
// budget is refused in microseconds: a profile's base level is held whole,
// so its face count is a lower bound on the profile's triangles.
#pragma once

#include <cstdint>

#include "core/hierarchy/ids.h"
#include "protocol/tessera.pb.h"
#include "server/base/config.h"
#include "server/base/serial_queue.h"

namespace tessera::server {

// Triangles of the uniform surface at `level`; beyond the counts' deepest
// level, four times per level, saturating.
int64_t uniformTriangles(const LevelCounts& counts, uint32_t level);

// Triangles a profile needs at least: its base level, held whole.
int64_t minimumTriangles(const LevelCounts& counts, const wire::LodProfile& profile);

// Triangles a profile may reach: its max level's, within its own budget or
// --max-triangles, whichever is smaller.
int64_t maximumTriangles(const LevelCounts& counts, const wire::LodProfile& profile, const Limits& limits);

// Work above --bulk-triangles goes to the bulk threads, so that a large
// document's heavy request never holds up another document's edits.
Lane laneFor(int64_t triangles, const ServerConfig& config);

}  // namespace tessera::server
