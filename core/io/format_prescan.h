// Strict pre-scans of OBJ, OFF, PLY and STL before OpenMesh reads them.
//
// OpenMesh's readers are lenient in ways that would silently change a mesh
// (dropping unparsable vertices and renumbering the rest, dropping faces,
// reading garbage counts from truncated files, looping on some PLY headers).
// Each pre-scan checks the whole file with line numbers and reports how many
// vertices and faces it declares, so the importer can compare what OpenMesh
// produced with what the file says.
#pragma once

#include <cstddef>
#include <string>

#include "core/util/status.h"

namespace tessera {

struct PrescanCounts {
  size_t vertices = 0;
  size_t faces = 0;
};

Status prescanObj(const std::string& text, const std::string& src, PrescanCounts& counts);
// OpenMesh's OFF reader knows no comments: `normalised` is the text it should read.
Status prescanOff(const std::string& text, const std::string& src, PrescanCounts& counts, std::string& normalised);
Status prescanPly(const std::string& text, const std::string& src, PrescanCounts& counts);
Status prescanStl(const std::string& text, const std::string& src, PrescanCounts& counts);

}  // namespace tessera
