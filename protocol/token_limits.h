// The one bound on an access token's length, for the Hello that carries it
// (docs/PROTOCOL.md §4.1) and for the store that grants it: a longer token
// is refused before it is hashed or looked up.
#pragma once

#include <cstddef>

namespace tessera {

inline constexpr size_t kMaxTokenBytes = 4096;

}  // namespace tessera
