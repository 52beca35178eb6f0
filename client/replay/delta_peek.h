// The version span of a Delta, read from a ServerMessage payload without
// parsing it (load tester, docs/REPLAY.md §3): a thousand counting viewers need only
// the document and the versions of each delta, not copies of its regions.
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

namespace tessera::replay {

struct DeltaHeader {
  uint64_t documentId = 0, fromVersion = 0, toVersion = 0;
  int64_t regions = 0;  // region payloads it carries (counted, not read)
};

// The header if `payload` is a well-formed ServerMessage holding a Delta;
// nullopt for any other message (parse it whole) or malformed bytes.
std::optional<DeltaHeader> peekDelta(std::string_view payload);

}  // namespace tessera::replay
