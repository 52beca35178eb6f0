#include "support/random_script.h"

#include <algorithm>
#include <cstdio>
#include <random>

namespace tessera::testing {

namespace {

std::string number(double x) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", x);
  return text;
}

}  // namespace

std::vector<std::string> randomScriptLines(const Document& doc, const QuantizationGrid& grid, int count,
                                           uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const LevelCounts& counts = doc.counts();
  const int deepest = std::min(2, doc.options().maxLevel - 1);
  auto vertex = [&](int level) {
    return "v" + std::to_string(level) + ":" + std::to_string(rng() % counts.vertices(level));
  };
  auto edge = [&](int level) {
    return "e" + std::to_string(level) + ":" + std::to_string(rng() % counts.edges(level));
  };
  const Vec3 center = grid.origin + (0.5 * grid.range) * Vec3(1, 1, 1);
  // Base vertices moved so far, and a triangle of each: creases and
  // corners next to them change the shape of the surface where it nears
  // the grid's faces, between the limits of the base vertices.
  std::vector<int> moved;
  std::vector<int> triangleOf(doc.baseTopology().numVertices, -1);
  for (size_t t = 0; t < doc.baseTopology().triangles.size(); ++t)
    for (int v : doc.baseTopology().triangles[t]) triangleOf[v] = static_cast<int>(t);
  auto edgeNextToMoved = [&]() -> std::string {
    const int v = moved[rng() % moved.size()];
    const auto& tri = doc.baseTopology().triangles[triangleOf[v]];
    const int w = tri[0] == v ? tri[1] : tri[0];
    auto e = doc.edgeBetween(VertexId(0, static_cast<uint64_t>(v)), VertexId(0, static_cast<uint64_t>(w)));
    return e.isOk() ? e->toString() : edge(0);
  };
  std::vector<std::string> lines;
  int made = 0;  // edits the lines would make if all were accepted: ids for undo and redo
  for (int i = 0; i < count; ++i) {
    const double pick = unit(rng);
    std::string line;
    if (pick < 0.45) {
      const int level = static_cast<int>(rng() % (deepest + 1));
      // A third aimed at the grid's faces, from just inside to just past.
      const bool edgeOfGrid = unit(rng) < 0.35;
      Vec3 target;
      for (int k = 0; k < 3; ++k) {
        const double side = unit(rng) < 0.5 ? -1.0 : 1.0;
        const double reach = edgeOfGrid ? 0.44 + 0.08 * unit(rng) : 0.3 * unit(rng);
        target[k] = center[k] + side * reach * grid.range;
      }
      const std::string v = vertex(level);
      if (level == 0 && edgeOfGrid) moved.push_back(std::stoi(v.substr(3)));
      line = "move " + v + " to " + number(target[0]) + " " + number(target[1]) + " " + number(target[2]);
      ++made;
    } else if (pick < 0.6) {
      const int level = 1 + static_cast<int>(rng() % deepest);
      const double size = 0.05 * grid.range;
      line = "offset " + vertex(level) + " by " + number(size * (2 * unit(rng) - 1)) + " " +
             number(size * (2 * unit(rng) - 1)) + " " + number(size * (2 * unit(rng) - 1));
      ++made;
    } else if (pick < 0.72) {
      const double s = unit(rng) < 0.2 ? 0.0 : 3.0 * unit(rng);
      const bool near = !moved.empty() && unit(rng) < 0.6;
      line = "crease " + (near ? edgeNextToMoved() : edge(static_cast<int>(rng() % 2))) + " " + number(s);
      ++made;
    } else if (pick < 0.78) {
      line = "corner " + vertex(static_cast<int>(rng() % 2)) + " " + number(unit(rng) < 0.5 ? 0.0 : 2.0);
      ++made;
    } else {
      const int id = 1 + static_cast<int>(rng() % static_cast<uint32_t>(made + 2));  // sometimes unknown
      line = std::string(unit(rng) < 0.6 ? "undo " : "redo ") + std::to_string(id);
    }
    lines.push_back(line);
  }
  return lines;
}

}  // namespace tessera::testing
