// The Binary glTF container (the glTF 2.0 specification, "GLB File Format
// Specification"): a 12-byte header, then chunks of an 8-byte header and
// a 4-byte-aligned body, the first JSON. Checked whole before a GLB goes to
// tinygltf, whose 2.7 reads a chunk that runs past the end of the buffer
// when the JSON chunk's length is not a multiple of 4 (docs/FUZZING.md).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "core/util/status.h"

namespace tessera::io_detail {

inline constexpr uint32_t kGlbMagic = 0x46546C67;      // "glTF"
inline constexpr uint32_t kGlbJsonChunk = 0x4E4F534A;  // "JSON"
inline constexpr size_t kGlbHeaderBytes = 12, kGlbChunkHeaderBytes = 8;

// The little-endian word at byte `at` (at + 4 <= data.size()).
uint32_t glbU32At(std::string_view data, size_t at);

// OK, or a parse error naming `name`, the chunk and its byte offset.
Status checkGlbContainer(std::string_view data, const std::string& name);

}  // namespace tessera::io_detail
