// Text for proto3 `string` fields, which must be valid UTF-8: a peer's
// parser refuses a message whose string is not (protobuf's
// wire_format_lite), so a server error quoting a client's bytes (a line of
// a mesh file, say) would break the client's stream instead of informing it.
#pragma once

#include <string>
#include <string_view>

namespace tessera {

bool isValidUtf8(std::string_view text);
// The text with every byte that is not part of a valid UTF-8 sequence
// written as "\xNN" (hex); valid text comes back unchanged.
std::string toValidUtf8(std::string_view text);

}  // namespace tessera
