// Sharp feature lines of a real triangle mesh as crease tags, for the
// viewer tests that show a CGAL mesh with its sharp edges tagged.
#pragma once

#include <array>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace tessera::testing {

namespace feature_detail {

struct OffVec {
  double x, y, z;
  OffVec operator-(const OffVec& o) const { return {x - o.x, y - o.y, z - o.z}; }
};
inline OffVec cross(const OffVec& a, const OffVec& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double dot(const OffVec& a, const OffVec& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
inline double norm(const OffVec& a) {
  return std::sqrt(dot(a, a));
}

}  // namespace feature_detail

// "crease I J inf" for every interior edge of a triangle OFF mesh whose two
// faces meet at more than `degrees` (fandisk's feature lines), read
// independently of Tessera's importers.
inline std::string featureTags(const std::string& offPath, double degrees, int& count) {
  using namespace feature_detail;
  std::ifstream in(offPath);
  std::string magic;
  size_t nv = 0, nf = 0, ne = 0;
  in >> magic >> nv >> nf >> ne;
  std::vector<OffVec> p(nv);
  for (auto& v : p) in >> v.x >> v.y >> v.z;
  std::vector<std::array<int, 3>> faces(nf);
  std::map<std::pair<int, int>, std::vector<int>> edgeFaces;
  for (size_t f = 0; f < nf; ++f) {
    int k = 0;
    in >> k >> faces[f][0] >> faces[f][1] >> faces[f][2];
    for (int e = 0; e < 3; ++e) {
      const int a = faces[f][e], b = faces[f][(e + 1) % 3];
      edgeFaces[{std::min(a, b), std::max(a, b)}].push_back(static_cast<int>(f));
    }
  }
  auto normal = [&](int f) {
    const OffVec n = cross(p[faces[f][1]] - p[faces[f][0]], p[faces[f][2]] - p[faces[f][0]]);
    const double l = norm(n);
    return OffVec{n.x / l, n.y / l, n.z / l};
  };
  std::ostringstream tags;
  count = 0;
  const double limit = std::cos(degrees * M_PI / 180.0);
  for (const auto& [edge, fs] : edgeFaces) {
    if (fs.size() != 2 || dot(normal(fs[0]), normal(fs[1])) > limit) continue;
    tags << "crease " << edge.first << " " << edge.second << " inf\n";
    ++count;
  }
  return tags.str();
}

}  // namespace tessera::testing
