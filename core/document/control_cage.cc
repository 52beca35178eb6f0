#include "core/document/control_cage.h"

#include <string>

namespace tessera {

Expected<ControlCage> controlCage(const Document& doc, int level) {
  const int maxLevel = doc.options().maxLevel;
  if (level < 0 || level > maxLevel) {
    return invalidArgument("control cage: level " + std::to_string(level) + " is outside the document's 0.." +
                           std::to_string(maxLevel));
  }
  // The dense evaluation numbers every level's vertices canonically (the
  // sparse hierarchy's ids are the same indices: docs/ARCHITECTURE.md),
  // and the document caches it until the next change.
  auto eval = doc.evaluate(level);
  if (!eval.isOk()) return eval.status().withContext("control cage");
  const Level& topology = (*eval)->levels[level];
  ControlCage cage;
  cage.level = level;
  cage.faceSizes.reserve(static_cast<size_t>(topology.numFaces()));
  cage.vertices.reserve(static_cast<size_t>(topology.numCorners()));
  for (Index f = 0; f < topology.numFaces(); ++f) {
    const auto corners = topology.faceVerticesOf(f);
    cage.faceSizes.push_back(static_cast<uint32_t>(corners.size()));
    for (Index v : corners) cage.vertices.push_back(static_cast<uint64_t>(v));
  }
  return cage;
}

}  // namespace tessera
