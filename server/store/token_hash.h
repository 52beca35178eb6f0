// Access tokens are bearer secrets: the store keeps only their SHA-256, so a
// copied database file or backup grants nothing. Tokens are expected to be
// long random strings; a plain (unsalted) hash is then as strong as the token
// and still lets a lookup go straight to the row by its primary key.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

#include "core/util/status.h"

namespace tessera::store {

inline constexpr size_t kTokenHashBytes = 32;

// The raw 32-byte SHA-256 digest of `token`. Errors never contain the token.
Expected<std::string> hashToken(std::string_view token);

}  // namespace tessera::store
