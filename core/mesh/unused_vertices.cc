#include "core/mesh/unused_vertices.h"

namespace tessera {

VertexRenumbering dropUnusedVertices(PolygonSoup& soup) {
  const int n = static_cast<int>(soup.points.size());
  std::vector<char> used(n, 0);
  VertexRenumbering renumbering;
  for (int index : soup.indices) {
    // A face naming a vertex that does not exist: leave the soup as the file
    // numbers it, so that validation's refusal names the file's indices.
    if (index < 0 || index >= n) return renumbering;
    used[index] = 1;
  }
  int kept = 0;
  for (char u : used) kept += u;
  if (kept == n) return renumbering;

  renumbering.newIndex.assign(n, -1);
  renumbering.dropped = n - kept;
  int next = 0;
  for (int v = 0; v < n; ++v) {
    if (!used[v]) continue;
    renumbering.newIndex[v] = next;
    soup.points[next++] = soup.points[v];
  }
  soup.points.resize(next);
  for (int& index : soup.indices) index = renumbering.newIndex[index];
  return renumbering;
}

}  // namespace tessera
