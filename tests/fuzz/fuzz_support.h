// Shared by the libFuzzer targets of tests/fuzz: the oracles every target
// applies besides the sanitizers, and the small documents they edit.
//
// Oracles: a target aborts (libFuzzer then saves the input) when a result
// breaks a documented promise, e.g. an error with ErrorCode::kInternal (by
// status.h's definition a broken invariant, a bug whatever the input) or an
// error with an empty message (every error must name what failed).
#pragma once

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "core/document/document.h"
#include "core/mesh/base_mesh.h"
#include "core/util/status.h"

namespace tessera::fuzz {

[[noreturn]] inline void fail(const std::string& what) {
  std::fprintf(stderr, "fuzz oracle: %s\n", what.c_str());
  std::abort();
}

inline void require(bool condition, const std::string& what) {
  if (!condition) fail(what);
}

// An error is fine for bad input, but it must say what failed and must not
// be a broken invariant.
inline void checkError(const Status& status, const char* where) {
  if (status.isOk()) return;
  if (status.message().empty()) fail(std::string(where) + ": an error with no message");
  if (status.code() == ErrorCode::kInternal)
    fail(std::string(where) + ": internal error: " + status.message());
}

inline std::string bytesOf(const uint8_t* data, size_t size) {
  return std::string(reinterpret_cast<const char*>(data), size);
}

// tests/data/cube.obj with cube.tags applied (two creases and a corner):
// sharp rules and smooth rules in twelve triangles. Read once per process.
const BaseMesh& creasedCube();

// The max level of the documents the host, journal and edit script targets
// edit. Level 2 (192 triangles) runs the same code as level 3 (every rule is
// level-generic) at a higher rate: the host target 177 against 85
// executions per second with close coverage (17,061 to 17,127 against 17,536
// edges after 40 s from the seeds; docs/FUZZING.md, session 10).
inline constexpr int kFuzzDocumentLevel = 2;

// A creased-cube document with this max level, created once per process and
// copied per input (creating one per input would dominate the run time).
const Document& cubeDocument(int maxLevel);

}  // namespace tessera::fuzz
