// docs/FORMATS.md "Mesh formats": a mesh far from the origin, read from each text format, has
// the limit normals OpenSubdiv gives on the same file's coordinates (parsed
// here with strtod, the definition) to 1e-8 rad. When OBJ and OFF were read
// as float, this fan's normals were 3.6e-4 rad away.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <sstream>

#include "core/io/mesh_import.h"
#include "core/loop/limit.h"
#include "oracle/osd_reference.h"

namespace tessera {
namespace {

constexpr double kNormalTolerance = 1e-8;  // radians

std::string g17(double x) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", x);
  return text;
}

// A 6-triangle fan of radius 0.05 around (1000, 1000, 1000) whose ring is
// not planar (the centre is raised), so the limit normals vary.
std::vector<Vec3> fan() {
  const Vec3 centre(1000.000000123456789, 999.99999987654321, 1000.0000000314159);
  const Vec3 u = Vec3(1, 0.3, -0.2).normalized();
  const Vec3 v = (Vec3(0.1, 0.2, 1) % u).normalized();
  const Vec3 w = (u % v).normalized();
  std::vector<Vec3> points = {centre + 0.01 * w};
  for (int k = 0; k < 6; ++k) {
    const double a = 2 * M_PI * k / 6 + 0.1;
    points.push_back(centre + 0.05 * (std::cos(a) * u + std::sin(a) * v) + (k % 2 ? 0.004 : -0.003) * w);
  }
  return points;
}

struct FanFile {
  std::string name, text;
  int firstVertexLine;
};

std::vector<FanFile> fanFiles() {
  std::string vertices, obj, off = "OFF\n7 6 0\n";
  for (const Vec3& p : fan()) vertices += g17(p[0]) + " " + g17(p[1]) + " " + g17(p[2]) + "\n";
  std::istringstream lines(vertices);
  for (std::string line; std::getline(lines, line);) obj += "v " + line + "\n";
  off += vertices;
  std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 7\nproperty double x\nproperty double y\nproperty double z\n"
      "element face 6\nproperty list uchar int vertex_indices\nend_header\n" +
      vertices;
  for (int k = 0; k < 6; ++k) {
    const int a = 1 + k, b = 1 + (k + 1) % 6;
    obj += "f 1 " + std::to_string(a + 1) + " " + std::to_string(b + 1) + "\n";
    off += "3 0 " + std::to_string(a) + " " + std::to_string(b) + "\n";
    ply += "3 0 " + std::to_string(a) + " " + std::to_string(b) + "\n";
  }
  return {{"fan.obj", obj, 0}, {"fan.off", off, 2}, {"fan.ply", ply, 9}};
}

// The file's coordinates by definition: strtod of the last three tokens of
// each vertex line.
std::vector<Vec3> strtodPoints(const FanFile& file) {
  std::istringstream in(file.text);
  std::string line;
  std::vector<Vec3> points;
  for (int n = 0; std::getline(in, line); ++n) {
    if (n < file.firstVertexLine || n >= file.firstVertexLine + 7) continue;
    std::istringstream tokens(line);
    std::vector<std::string> all;
    for (std::string t; tokens >> t;) all.push_back(t);
    const size_t k = all.size() - 3;
    points.emplace_back(std::strtod(all[k].c_str(), nullptr), std::strtod(all[k + 1].c_str(), nullptr),
                        std::strtod(all[k + 2].c_str(), nullptr));
  }
  return points;
}

double angleBetween(const Vec3& a, const Vec3& b) {
  return std::atan2((a % b).norm(), a | b);
}

// The worst angle between Tessera's limit normals from `ours` (the points it
// evaluates) and OpenSubdiv's from `reference` (the file's), levels 0 to 2.
double worstNormalAngle(const BaseMesh& mesh, const std::vector<Vec3>& ours,
                        const std::vector<Vec3>& reference, int& compared) {
  const BaseTopology topology = BaseTopology::fromBaseMesh(mesh);
  auto refiner = LoopRefiner::create(topology, LoopOptions{}, {.levels = 2});
  EXPECT_TRUE(refiner.isOk()) << refiner.status().toString();
  auto osd = oracle::refineWithOpenSubdiv(topology, reference, LoopOptions{}, *refiner, true);
  auto points = refiner->refinePointsPerLevel(ours);
  double worst = 0;
  for (int l = 0; l <= 2; ++l) {
    const Level& level = refiner->level(l);
    for (int v = 0; v < level.numVertices; ++v) {
      const Vec3 cross = osd[l].limitTangent1[v] % osd[l].limitTangent2[v];
      if (cross.norm() <= 1e-8 * osd[l].limitTangent1[v].norm() * osd[l].limitTangent2[v].norm()) continue;
      worst = std::max(worst, angleBetween(limitFrame(level, v, points[l]).normal(), cross));
      ++compared;
    }
  }
  return worst;
}

TEST(FarFromOrigin, LimitNormalsMatchOpenSubdivOnTheFilesCoordinates) {
  for (const FanFile& file : fanFiles()) {
    SCOPED_TRACE(file.name);
    auto mesh =
        importMeshFromBytes(file.text, std::filesystem::path(file.name).extension().string(), file.name);
    ASSERT_TRUE(mesh.isOk()) << mesh.status().toString();
    const std::vector<Vec3> reference = strtodPoints(file);
    ASSERT_EQ(mesh->positions(), reference);
    int compared = 0;
    const double worst = worstNormalAngle(*mesh, mesh->positions(), reference, compared);
    // The same comparison with the coordinates rounded to float, as the
    // readers did before: it must fail, or this test could not.
    std::vector<Vec3> asFloat;
    for (const Vec3& p : reference) asFloat.emplace_back(float(p[0]), float(p[1]), float(p[2]));
    int comparedFloat = 0;
    const double worstFloat = worstNormalAngle(*mesh, asFloat, reference, comparedFloat);
    std::cout << "[ far      ] " << file.name << ": worst limit normal " << worst << " rad over " << compared
              << " vertices (read as float: " << worstFloat << " rad)\n";
    EXPECT_GT(compared, 50);
    EXPECT_LE(worst, kNormalTolerance);
    EXPECT_GT(worstFloat, 100 * kNormalTolerance);
  }
}

}  // namespace
}  // namespace tessera
