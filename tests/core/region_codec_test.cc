// Region codec (docs/REGION_ENCODING.md): round trips, bit-identical
// borders between separately encoded regions, the quantization bound, and
// rejection of truncated, corrupted and foreign bytes.
//
// Stated bounds:
//   positions: within grid.maxPositionError() of the input, itself at most
//              1e-4 of the bounding-box diagonal for grids from gridFor;
//   normals:   within 3 sqrt(2) / (2^bits - 2) radians (0.238 degrees at the
//              default 10 bits), plus 2% for float32. Draco's octahedral
//              coordinates have a step of 2 / (2^bits - 2); rounding moves a
//              normal by at most sqrt(2) / (2^bits - 2) in the unfolded
//              square, and mapping back onto the sphere stretches that at
//              most 3x (near the octahedron's face centres, at 1/sqrt(3) from
//              the origin). 90k random normals reach 98% of it.
#include <draco/compression/decode.h>
#include <gtest/gtest.h>
#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <iostream>
#include <map>
#include <random>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "core/hierarchy/ids.h"
#include "core/tessellation/region_codec.h"
#include "support/region_checks.h"
#include "support/region_meshes.h"

namespace tessera {
namespace {

using testing::refreshRegionChecksum;
using testing::trianglesOverIds;

constexpr double kDegrees = 180.0 / 3.14159265358979323846;

double normalBoundDegrees(int normalBits) {
  return 1.02 * 3.0 * std::sqrt(2.0) / (std::ldexp(1.0, normalBits) - 2.0) * kDegrees;
}

// A closed smooth surface (region_meshes.h's torus limit) and its box.
struct Surface {
  std::vector<Vec3> positions;
  std::vector<Vec3> normals;
  std::vector<uint64_t> ids;
  std::vector<std::array<int, 3>> triangles;
  Vec3 bboxMin, bboxMax;
};

Surface torusSurface(int levels) {
  RegionMesh m = testing::torusLimitRegion(levels);
  Surface s;
  s.positions = std::move(m.positions);
  s.normals = std::move(m.normals);
  s.ids = std::move(m.vertexIds);
  s.triangles = std::move(m.triangles);
  s.bboxMin = s.bboxMax = s.positions[0];
  for (const Vec3& p : s.positions) s.bboxMin.minimize(p), s.bboxMax.maximize(p);
  return s;
}

// Splits the surface into `count` sectors around the torus axis by the angle
// of each triangle's centroid: every sector shares two borders.
std::vector<RegionMesh> splitIntoSectors(const Surface& s, int count) {
  std::vector<RegionMesh> regions(count);
  std::vector<std::vector<int>> local(count, std::vector<int>(s.positions.size(), -1));
  for (const auto& t : s.triangles) {
    const Vec3 c = (s.positions[t[0]] + s.positions[t[1]] + s.positions[t[2]]) / 3.0;
    const double angle = std::atan2(c[1], c[0]) + M_PI;  // [0, 2 pi]
    const int r = std::min(count - 1, static_cast<int>(angle / (2 * M_PI) * count));
    std::array<int, 3> mapped{};
    for (int k = 0; k < 3; ++k) {
      int& index = local[r][t[k]];
      if (index < 0) {
        index = static_cast<int>(regions[r].positions.size());
        regions[r].positions.push_back(s.positions[t[k]]);
        regions[r].normals.push_back(s.normals[t[k]]);
        regions[r].vertexIds.push_back(s.ids[t[k]]);
      }
      mapped[k] = index;
    }
    regions[r].triangles.push_back(mapped);
  }
  return regions;
}

RegionMesh wholeSurface(const Surface& s) {
  return {s.positions, s.normals, s.ids, s.triangles};
}

RegionHeader headerFor(const Surface& s, uint64_t regionId) {
  RegionHeader header;
  header.regionId = regionId;
  header.documentVersion = 42;
  header.profile.baseLevel = 1;
  header.profile.maxLevel = 4;
  header.profile.angleThresholdDegrees = 7.5;
  header.profile.triangleBudget = 123456;
  header.profile.fidelity = true;
  auto grid = gridFor(s.bboxMin, s.bboxMax);
  EXPECT_TRUE(grid.isOk()) << grid.status().toString();
  header.grid = *grid;
  return header;
}

double angleDegrees(const Vec3& a, const Vec3& b) {
  return std::atan2(cross(a, b).norm(), dot(a, b)) * kDegrees;
}

// Largest position error and normal angle of a decoded region against the
// input, matched by id (each id is one vertex of the input).
std::pair<double, double> decodedErrors(const RegionMesh& input, const RegionMesh& decoded) {
  std::map<uint64_t, size_t> byId;
  for (size_t i = 0; i < input.vertexIds.size(); ++i) byId[input.vertexIds[i]] = i;
  double position = 0.0, normal = 0.0;
  for (size_t i = 0; i < decoded.vertexIds.size(); ++i) {
    const auto it = byId.find(decoded.vertexIds[i]);
    EXPECT_NE(it, byId.end()) << "decoded id " << VertexId::fromPacked(decoded.vertexIds[i]).toString();
    if (it == byId.end()) continue;
    position = std::max(position, (decoded.positions[i] - input.positions[it->second]).norm());
    normal = std::max(normal, angleDegrees(decoded.normals[i], input.normals[it->second]));
  }
  return {position, normal};
}

std::pair<RegionHeader, RegionMesh> roundTrip(const RegionHeader& header, const RegionMesh& mesh, int level) {
  auto bytes = encodeRegion(header, mesh, level);
  EXPECT_TRUE(bytes.isOk()) << bytes.status().toString();
  if (!bytes.isOk()) return {};
  auto decoded = decodeRegion(*bytes);
  EXPECT_TRUE(decoded.isOk()) << decoded.status().toString();
  if (!decoded.isOk()) return {};
  return std::move(decoded).value();
}

TEST(RegionCodec, RoundTripKeepsHeaderIdsAndTriangles) {
  const Surface s = torusSurface(2);
  const RegionMesh region = splitIntoSectors(s, 4)[1];
  const RegionHeader header = headerFor(s, 0xFEDCBA9876543210ull);
  const double diagonal = (s.bboxMax - s.bboxMin).norm();
  EXPECT_EQ(header.grid.positionBits, 13);
  for (int level : {0, 1, 5, kDefaultRegionCompressionLevel, 10}) {
    SCOPED_TRACE("compression level " + std::to_string(level));
    const auto [decodedHeader, decoded] = roundTrip(header, region, level);
    EXPECT_EQ(decodedHeader, header);
    EXPECT_EQ(decoded.triangles.size(), region.triangles.size());
    EXPECT_EQ(trianglesOverIds(decoded), trianglesOverIds(region));
    EXPECT_EQ(std::set<uint64_t>(decoded.vertexIds.begin(), decoded.vertexIds.end()),
              std::set<uint64_t>(region.vertexIds.begin(), region.vertexIds.end()));
    const auto [position, normal] = decodedErrors(region, decoded);
    EXPECT_LE(position, header.grid.maxPositionError());
    EXPECT_LE(position, 1e-4 * diagonal);
    EXPECT_LE(normal, normalBoundDegrees(header.grid.normalBits));
    for (const Vec3& n : decoded.normals) EXPECT_NEAR(n.norm(), 1.0, 1e-12);
    if (level == kDefaultRegionCompressionLevel) {
      std::cout << "[ measured ] " << region.triangles.size() << " triangles: position error " << position
                << " = " << position / diagonal << " of the diagonal (bound "
                << header.grid.maxPositionError() << "), normal error " << normal << " degrees\n";
    }
  }
}

TEST(RegionCodec, ExtremeVertexIdsSurviveExactly) {
  const Surface s = torusSurface(1);
  RegionMesh region = wholeSurface(s);
  std::mt19937_64 rng(5);
  for (size_t i = 0; i < region.vertexIds.size(); ++i) region.vertexIds[i] = rng();
  region.vertexIds[0] = 0;
  region.vertexIds[1] = ~uint64_t{0};
  region.vertexIds[2] = VertexId(kMaxIdLevel, VertexId::kIndexMask).packed();
  region.vertexIds[3] = uint64_t{1} << 63;
  const RegionHeader header = headerFor(s, 3);
  for (int level : {0, 10}) {
    const auto [decodedHeader, decoded] = roundTrip(header, region, level);
    EXPECT_EQ(trianglesOverIds(decoded), trianglesOverIds(region));
    EXPECT_EQ(std::multiset<uint64_t>(decoded.vertexIds.begin(), decoded.vertexIds.end()),
              std::multiset<uint64_t>(region.vertexIds.begin(), region.vertexIds.end()));
  }
}

TEST(RegionCodec, NonManifoldAndDisconnectedRegionsKeepTheirTriangles) {
  const RegionMesh m = testing::bowTieAndIsland();
  RegionHeader header;
  header.grid = *gridFor({-1, -1, 0}, {3, 3, 0});
  for (int level = 0; level <= 10; ++level) {
    const auto [decodedHeader, decoded] = roundTrip(header, m, level);
    EXPECT_EQ(trianglesOverIds(decoded), trianglesOverIds(m)) << "level " << level;
    const auto [position, normal] = decodedErrors(m, decoded);
    EXPECT_LE(position, header.grid.maxPositionError());
  }
}

TEST(RegionCodec, SharedBordersDecodeBitIdenticallyAndTheUnionIsCrackFree) {
  const Surface s = torusSurface(3);
  for (int count : {2, 5, 8}) {
    SCOPED_TRACE(std::to_string(count) + " regions");
    const std::vector<RegionMesh> regions = splitIntoSectors(s, count);
    const RegionHeader shared = headerFor(s, 0);
    std::map<uint64_t, Vec3> decodedById;
    std::map<uint64_t, int> regionsById;
    std::map<std::pair<uint64_t, uint64_t>, int> directedById;
    std::map<std::pair<std::array<double, 3>, std::array<double, 3>>, int> edgesByPosition;
    size_t triangles = 0, borderChecks = 0;
    for (int r = 0; r < count; ++r) {
      RegionHeader header = shared;
      header.regionId = static_cast<uint64_t>(r);
      // Alternate levels: the lattice, not the coder, decides the positions.
      const auto [decodedHeader, decoded] = roundTrip(header, regions[r], r % 2 == 0 ? 0 : 10);
      ASSERT_EQ(decoded.triangles.size(), regions[r].triangles.size());
      triangles += decoded.triangles.size();
      std::set<uint64_t> seen;
      for (size_t i = 0; i < decoded.vertexIds.size(); ++i) {
        const uint64_t id = decoded.vertexIds[i];
        const auto [it, inserted] = decodedById.emplace(id, decoded.positions[i]);
        if (!inserted) {
          // Bit-identical, not merely close.
          EXPECT_EQ(std::memcmp(it->second.data(), decoded.positions[i].data(), sizeof(double) * 3), 0)
              << VertexId::fromPacked(id).toString();
          ++borderChecks;
        }
        if (seen.insert(id).second) ++regionsById[id];
      }
      for (const auto& t : decoded.triangles) {
        for (int k = 0; k < 3; ++k) {
          const int a = t[k], b = t[(k + 1) % 3];
          ++directedById[{decoded.vertexIds[a], decoded.vertexIds[b]}];
          const Vec3& pa = decoded.positions[a];
          const Vec3& pb = decoded.positions[b];
          std::array<double, 3> ka{pa[0], pa[1], pa[2]}, kb{pb[0], pb[1], pb[2]};
          if (kb < ka) std::swap(ka, kb);
          ++edgesByPosition[{ka, kb}];
        }
      }
    }
    EXPECT_EQ(triangles, s.triangles.size());
    const size_t shared2 =
        std::count_if(regionsById.begin(), regionsById.end(), [](auto& e) { return e.second > 1; });
    EXPECT_GT(shared2, 0u);
    EXPECT_GE(borderChecks, shared2);
    // Closed, manifold and consistently oriented: every directed edge once,
    // its reverse once; keyed by decoded positions, every edge twice.
    for (const auto& [edge, n] : directedById) {
      EXPECT_EQ(n, 1);
      EXPECT_EQ(directedById.count({edge.second, edge.first}), 1u);
    }
    EXPECT_EQ(directedById.size(), 3 * s.triangles.size());
    for (const auto& [edge, n] : edgesByPosition) EXPECT_EQ(n, 2);
    EXPECT_EQ(2 * edgesByPosition.size(), 3 * s.triangles.size());
  }
}

TEST(RegionCodec, DecodedPositionsMatchAPlainDracoDecoder) {
  const Surface s = torusSurface(2);
  const RegionHeader header = headerFor(s, 9);
  auto bytes = encodeRegion(header, wholeSurface(s));
  ASSERT_TRUE(bytes.isOk());
  auto decoded = decodeRegion(*bytes);
  ASSERT_TRUE(decoded.isOk());
  draco::DecoderBuffer buffer;
  buffer.Init(bytes->data() + kRegionHeaderBytes, bytes->size() - kRegionHeaderBytes - kRegionTrailerBytes);
  draco::Decoder decoder;
  auto plain = decoder.DecodeMeshFromBuffer(&buffer);
  ASSERT_TRUE(plain.ok());
  const draco::PointAttribute* positions =
      plain.value()->GetNamedAttribute(draco::GeometryAttribute::POSITION);
  ASSERT_EQ(plain.value()->num_points(), decoded->second.positions.size());
  for (draco::PointIndex p(0); p < plain.value()->num_points(); ++p) {
    float value[3];
    positions->GetValue(positions->mapped_index(p), value);
    for (int k = 0; k < 3; ++k)
      ASSERT_EQ(static_cast<double>(value[k]), decoded->second.positions[p.value()][k]);
  }
}

// Points spread over the box (corners included), as triangles of three.
RegionMesh pointsIn(const Vec3& lo, const Vec3& hi, int count, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  RegionMesh m;
  for (int i = 0; i < count; ++i) {
    Vec3 p;
    for (int k = 0; k < 3; ++k)
      p[k] = i < 8 ? ((i >> k) & 1 ? hi[k] : lo[k]) : lo[k] + (hi[k] - lo[k]) * unit(rng);
    m.positions.push_back(p);
    m.normals.push_back(Vec3(unit(rng) - 0.5, unit(rng) - 0.5, unit(rng) + 0.1).normalized());
    m.vertexIds.push_back(VertexId(2, i).packed());
  }
  for (int i = 0; i + 2 < count; i += 3) m.triangles.push_back({i, i + 1, i + 2});
  return m;
}

TEST(RegionCodec, GridBitsMeetTheErrorBoundOnDecodedData) {
  struct Box {
    Vec3 lo, hi;
  };
  const Box boxes[] = {
      {{0, 0, 0}, {1, 1, 1}},
      {{-50, -50, -0.005}, {50, 50, 0.005}},
      {{100, 100, 100}, {101, 101, 101}},
      {{-3e-4, 1e-4, 0}, {7e-4, 2e-4, 5e-4}},
      {{-2, -1, 0}, {3, 0.5, 0}},  // flat: zero extent on z
  };
  for (const Box& box : boxes) {
    auto grid = gridFor(box.lo, box.hi);
    ASSERT_TRUE(grid.isOk()) << grid.status().toString();
    const double diagonal = (box.hi - box.lo).norm();
    const double target = 1e-4 * diagonal;
    EXPECT_LE(grid->maxPositionError(), target);
    // Minimal: one bit less misses the bound.
    QuantizationGrid coarser = *grid;
    --coarser.positionBits;
    EXPECT_GT(coarser.maxPositionError(), target);

    RegionHeader header;
    header.grid = *grid;
    const RegionMesh m = pointsIn(box.lo, box.hi, 3000, 17);
    const auto [decodedHeader, decoded] = roundTrip(header, m, 7);
    const auto [position, normal] = decodedErrors(m, decoded);
    EXPECT_LE(position, grid->maxPositionError());
    EXPECT_LE(normal, normalBoundDegrees(grid->normalBits));
    std::cout << "[ measured ] box " << box.lo[0] << ".." << box.hi[0] << ": " << grid->positionBits
              << " bits, decoded error " << position / diagonal << " of the diagonal (bound "
              << grid->maxPositionError() / diagonal << "), normal error " << normal << " degrees\n";
  }
  // A unit box 1e4 from the origin: float32 steps there are 1e-3, beyond 1e-4.
  auto far = gridFor({1e4, 1e4, 1e4}, {1e4 + 1, 1e4 + 1, 1e4 + 1});
  ASSERT_FALSE(far.isOk());
  EXPECT_NE(far.status().message().find("float32"), std::string::npos) << far.status().toString();
  for (const auto& [lo, hi, fraction] :
       {std::tuple{Vec3(0, 0, 0), Vec3(0, 0, 0), 1e-4}, std::tuple{Vec3(1, 0, 0), Vec3(0, 1, 1), 1e-4},
        std::tuple{Vec3(0, 0, 0), Vec3(NAN, 1, 1), 1e-4}, std::tuple{Vec3(0, 0, 0), Vec3(1, 1, 1), 0.0}}) {
    EXPECT_EQ(gridFor(lo, hi, fraction).status().code(), ErrorCode::kInvalidArgument);
  }
}

TEST(RegionCodec, HighlyCompressibleRegionsStayWithinTheDecoderBound) {
  // A planar regular grid whose vertices sit exactly on the quantization
  // lattice, all with one id (ids need not be distinct: crease copies share
  // theirs): every Draco predictor is exact, which gives the fewest bytes per
  // triangle found, and the decoder's count bound must leave room for it.
  RegionHeader header;
  header.grid = *gridFor({0, 0, 0}, {1, 1, 0});
  const double step = header.grid.range / ((1 << header.grid.positionBits) - 1);
  const int n = 256;
  RegionMesh m;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      m.positions.push_back(header.grid.origin + Vec3(i + 10, j + 10, 10) * step);
      m.normals.push_back(Vec3(0, 0, 1));
      m.vertexIds.push_back(VertexId(4, 7).packed());
    }
  }
  for (int i = 0; i + 1 < n; ++i) {
    for (int j = 0; j + 1 < n; ++j) {
      const int a = i * n + j;
      m.triangles.push_back({a, a + n, a + n + 1});
      m.triangles.push_back({a, a + n + 1, a + 1});
    }
  }
  for (int level : {7, 10}) {
    auto bytes = encodeRegion(header, m, level);
    ASSERT_TRUE(bytes.isOk()) << bytes.status().toString();
    const auto decoded = decodeRegion(*bytes);
    ASSERT_TRUE(decoded.isOk()) << decoded.status().toString();
    EXPECT_EQ(decoded->second.triangles.size(), m.triangles.size());
    // Far beyond what a byte of a typical region holds (about 1/3 triangle).
    EXPECT_GT(m.triangles.size(), 64 * bytes->size());
    std::cout << "[ measured ] lattice-aligned grid, level " << level << ": " << m.triangles.size()
              << " triangles in " << bytes->size() << " bytes\n";
  }
}

Status encodeStatus(const RegionHeader& header, const RegionMesh& mesh, int level = 5) {
  return encodeRegion(header, mesh, level).status();
}

TEST(RegionCodec, RejectsInvalidInputWithClearErrors) {
  const Surface s = torusSurface(1);
  const RegionHeader header = headerFor(s, 77);
  const RegionMesh good = wholeSurface(s);
  ASSERT_TRUE(encodeStatus(header, good).isOk());
  const auto expectError = [&](const RegionHeader& h, const RegionMesh& m, ErrorCode code,
                               const std::string& words, int level = 5) {
    const Status status = encodeStatus(h, m, level);
    EXPECT_EQ(status.code(), code) << status.toString();
    EXPECT_NE(status.message().find(words), std::string::npos) << status.toString();
    EXPECT_NE(status.message().find("region 77"), std::string::npos) << status.toString();
  };
  RegionMesh m = good;
  m.positions[5][1] = NAN;
  expectError(header, m, ErrorCode::kInvalidMesh, "vertex 5 (v1:5): position");
  m = good;
  m.positions[6][2] = INFINITY;
  expectError(header, m, ErrorCode::kInvalidMesh, "not finite");
  m = good;
  m.normals[7] = Vec3(0, NAN, 1);
  expectError(header, m, ErrorCode::kInvalidMesh, "vertex 7 (v1:7): normal");
  m = good;
  m.normals[7] = Vec3(0, 0, 2);
  expectError(header, m, ErrorCode::kInvalidMesh, "has length 2");
  m = good;
  m.positions[3] = header.grid.origin - Vec3(1e-9, 0, 0);
  expectError(header, m, ErrorCode::kInvalidMesh, "outside the quantization grid");
  m = good;
  m.positions[3] = header.grid.origin + Vec3(0, header.grid.range * 1.0000001, 0);
  expectError(header, m, ErrorCode::kInvalidMesh, "outside the quantization grid");
  m = good;
  m.triangles[4][1] = static_cast<int>(m.positions.size());
  expectError(header, m, ErrorCode::kInvalidMesh, "triangle 4: index");
  m = good;
  m.triangles[4][2] = -1;
  expectError(header, m, ErrorCode::kInvalidMesh, "outside [0,");
  m = good;
  m.triangles[2][2] = m.triangles[2][0];
  expectError(header, m, ErrorCode::kInvalidMesh, "repeats a vertex");
  m = good;
  m.normals.pop_back();
  expectError(header, m, ErrorCode::kInvalidMesh, "normals for");
  m = good;
  m.vertexIds.push_back(1);
  expectError(header, m, ErrorCode::kInvalidMesh, "vertex ids for");
  m = good;
  m.positions.push_back(m.positions[0]);
  m.normals.push_back(m.normals[0]);
  m.vertexIds.push_back(12345);
  expectError(header, m, ErrorCode::kInvalidMesh, "used by no triangle");
  expectError(header, RegionMesh{}, ErrorCode::kInvalidMesh, "no triangles");
  expectError(header, good, ErrorCode::kInvalidArgument, "compression level 11", 11);
  expectError(header, good, ErrorCode::kInvalidArgument, "compression level -1", -1);
  RegionHeader h = header;
  h.profile.maxLevel = 0;
  expectError(h, good, ErrorCode::kInvalidArgument, "LOD profile");
  h = header;
  h.grid.origin[0] = 0.1;  // not a float32 value
  expectError(h, good, ErrorCode::kInvalidArgument, "float32");
  h = header;
  h.grid.positionBits = 0;
  expectError(h, good, ErrorCode::kInvalidArgument, "positionBits 0");
  h = header;
  h.grid.normalBits = 1;
  expectError(h, good, ErrorCode::kInvalidArgument, "normalBits 1");
  h = header;
  h.grid.positionBits = 24;  // finer than float32 resolves at this scale
  expectError(h, good, ErrorCode::kInvalidArgument, "finer than float32");
}

// A small region (tens of triangles), so that every truncation and thousands
// of mutations decode in well under a second.
std::string smallEncoding(int level = kDefaultRegionCompressionLevel) {
  const Surface s = torusSurface(1);
  const RegionMesh region = splitIntoSectors(s, 8)[3];
  auto bytes = encodeRegion(headerFor(s, 5), region, level);
  EXPECT_TRUE(bytes.isOk()) << bytes.status().toString();
  return bytes.isOk() ? *bytes : std::string();
}

// A display-only profile's regions carry no ids: the same triangles over
// the same decoded positions and normals, fewer bytes; a flag the decoder
// does not know, or a flag that disagrees with the payload, is refused.
TEST(RegionCodec, DisplayOnlyRegionsOmitIdsAndKeepTheGeometry) {
  const Surface s = torusSurface(2);
  const RegionMesh region = splitIntoSectors(s, 4)[1];
  const RegionHeader withIds = headerFor(s, 77);
  RegionHeader displayOnly = withIds;
  displayOnly.profile.vertexIds = false;
  auto full = encodeRegion(withIds, region);
  auto thin = encodeRegion(displayOnly, region);
  ASSERT_TRUE(full.isOk() && thin.isOk());
  auto a = decodeRegion(*full);
  auto b = decodeRegion(*thin);
  ASSERT_TRUE(a.isOk() && b.isOk()) << b.status().toString();
  EXPECT_EQ(b->first, displayOnly);
  EXPECT_FALSE(b->first.profile.vertexIds);
  EXPECT_TRUE(b->second.vertexIds.empty());
  EXPECT_EQ(b->second.triangles.size(), region.triangles.size());
  // Same geometry: every decoded triangle's corners (positions and
  // normals, bit for bit) appear in both decodes.
  auto corners = [](const RegionMesh& m) {
    std::multiset<std::array<double, 6>> out;
    for (const auto& t : m.triangles) {
      for (int k = 0; k < 3; ++k) {
        const Vec3& p = m.positions[t[k]];
        const Vec3& n = m.normals[t[k]];
        out.insert({p[0], p[1], p[2], n[0], n[1], n[2]});
      }
    }
    return out;
  };
  EXPECT_EQ(corners(a->second), corners(b->second));
  EXPECT_LT(thin->size(), full->size());
  std::cout << "[ measured ] " << region.triangles.size() << " triangles: " << full->size()
            << " bytes with ids, " << thin->size() << " display-only\n";

  std::string unknownFlag = *thin;
  unknownFlag[6] = 16;  // the flags follow the magic and the version
  refreshRegionChecksum(unknownFlag);
  auto refused = decodeRegion(unknownFlag);
  EXPECT_EQ(refused.status().code(), ErrorCode::kParseError);
  EXPECT_NE(refused.status().message().find("unknown flags 16"), std::string::npos)
      << refused.status().toString();
  std::string noFlag = *thin;
  noFlag[6] = 0;  // claims ids the payload does not hold
  refreshRegionChecksum(noFlag);
  refused = decodeRegion(noFlag);
  EXPECT_EQ(refused.status().code(), ErrorCode::kParseError);
  EXPECT_NE(refused.status().message().find("attributes"), std::string::npos) << refused.status().toString();
}

// A region that only moved keeps its layout (triangles over ids): its
// payload leaves the ids out and the receiver adopts those of the copy it
// holds. This rests on Draco decoding the same connectivity in the same
// order whatever the attribute values; the check is against an encoding of
// the moved region with its ids, vertex by vertex, at every compression
// level and on several regions.
TEST(RegionCodec, LayoutIdsAreAdoptedInTheDecodedOrder) {
  const Surface s = torusSurface(2);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> jitter(-0.02, 0.02);
  for (const RegionMesh& region : splitIntoSectors(s, 3)) {
    RegionMesh moved = region;
    for (size_t v = 0; v < moved.positions.size(); ++v) {
      moved.positions[v] += moved.normals[v] * jitter(rng);
      moved.normals[v] = (moved.normals[v] + Vec3(jitter(rng), jitter(rng), jitter(rng))).normalized();
    }
    for (int level : {0, 3, 7, 10}) {
      RegionHeader layout = headerFor(s, 5);
      layout.documentVersion = layout.layoutVersion = 7;
      const auto held = roundTrip(layout, region, level).second;
      RegionHeader later = layout;
      later.documentVersion = 9;
      later.idsInline = false;
      auto thin = encodeRegion(later, moved, level);
      RegionHeader inlined = later;
      inlined.idsInline = true;
      auto full = encodeRegion(inlined, moved, level);
      ASSERT_TRUE(thin.isOk() && full.isOk()) << thin.status().toString();
      EXPECT_LT(thin->size(), full->size());
      auto decoded = decodeRegion(*thin);
      ASSERT_TRUE(decoded.isOk()) << decoded.status().toString();
      EXPECT_EQ(decoded->first, later);
      EXPECT_TRUE(decoded->second.vertexIds.empty());
      ASSERT_TRUE(adoptLayoutIds(decoded->first, decoded->second, held, 7).isOk());
      auto reference = decodeRegion(*full);
      ASSERT_TRUE(reference.isOk());
      EXPECT_EQ(decoded->second.vertexIds, reference->second.vertexIds) << "level " << level;
      EXPECT_EQ(decoded->second.triangles, reference->second.triangles);
      ASSERT_EQ(decoded->second.positions.size(), reference->second.positions.size());
      for (size_t v = 0; v < decoded->second.positions.size(); ++v) {
        EXPECT_EQ(decoded->second.positions[v], reference->second.positions[v]) << v;
      }
      if (level == 3) {
        std::cout << "[ measured ] " << region.triangles.size() << " triangles moved: " << full->size()
                  << " bytes with ids, " << thin->size() << " with the layout's\n";
      }
    }
  }
}

TEST(RegionCodec, LayoutIdsRefuseAnotherLayoutAndBadFlags) {
  const Surface s = torusSurface(2);
  const auto sectors = splitIntoSectors(s, 4);
  RegionHeader header = headerFor(s, 5);
  header.layoutVersion = 40;
  const auto held = roundTrip(header, sectors[0], 3).second;
  const auto other = roundTrip(header, splitIntoSectors(s, 3)[0], 3).second;  // more triangles
  header.idsInline = false;
  auto thin = encodeRegion(header, sectors[0]);
  ASSERT_TRUE(thin.isOk());
  auto decoded = decodeRegion(*thin);
  ASSERT_TRUE(decoded.isOk());
  RegionMesh mesh = decoded->second;
  Status status = adoptLayoutIds(decoded->first, mesh, held, 39);
  EXPECT_EQ(status.code(), ErrorCode::kInvalidArgument);
  EXPECT_NE(status.message().find("layout 40, the receiver holds layout 39"), std::string::npos)
      << status.toString();
  status = adoptLayoutIds(decoded->first, mesh, other, 40);
  EXPECT_NE(status.message().find("triangles differ"), std::string::npos) << status.toString();
  EXPECT_TRUE(mesh.vertexIds.empty());
  EXPECT_TRUE(adoptLayoutIds(decoded->first, mesh, held, 40).isOk());
  EXPECT_EQ(mesh.vertexIds.size(), mesh.positions.size());

  // The encoder refuses a layout later than the document and layout ids in
  // a display-only profile.
  RegionHeader bad = header;
  bad.layoutVersion = 43;
  status = encodeRegion(bad, sectors[0]).status();
  EXPECT_EQ(status.code(), ErrorCode::kInvalidArgument);
  EXPECT_NE(status.message().find("layout version 43 is later than the document version 42"),
            std::string::npos)
      << status.toString();
  bad = header;
  bad.profile.vertexIds = false;
  status = encodeRegion(bad, sectors[0]).status();
  EXPECT_NE(status.message().find("only in a profile with vertex ids"), std::string::npos)
      << status.toString();

  // The decoder refuses two flags at once, a flag that disagrees with the
  // payload, and a layout later than the document.
  std::string both = *thin;
  both[6] = 3;
  refreshRegionChecksum(both);
  status = decodeRegion(both).status();
  EXPECT_EQ(status.code(), ErrorCode::kParseError);
  EXPECT_NE(status.message().find("more than one way"), std::string::npos) << status.toString();
  RegionHeader inlined = header;
  inlined.idsInline = true;
  auto full = encodeRegion(inlined, sectors[0]);
  ASSERT_TRUE(full.isOk());
  std::string claims = *full;
  claims[6] = 2;  // the layout's ids, yet the payload holds ids
  refreshRegionChecksum(claims);
  status = decodeRegion(claims).status();
  EXPECT_NE(status.message().find("attributes"), std::string::npos) << status.toString();
  std::string late = *thin;
  const uint64_t layout = 99;
  std::memcpy(late.data() + 24, &layout, 8);
  refreshRegionChecksum(late);
  status = decodeRegion(late).status();
  EXPECT_EQ(status.code(), ErrorCode::kParseError);
  EXPECT_NE(status.message().find("layout version 99 is later"), std::string::npos) << status.toString();
}

TEST(RegionCodec, RejectsEveryTruncation) {
  for (int level : {0, 10}) {
    const std::string bytes = smallEncoding(level);
    ASSERT_TRUE(decodeRegion(bytes).isOk());
    for (size_t length = 0; length < bytes.size(); ++length) {
      const auto decoded = decodeRegion(std::string_view(bytes).substr(0, length));
      ASSERT_FALSE(decoded.isOk()) << "length " << length;
      EXPECT_EQ(decoded.status().code(), ErrorCode::kParseError);
      EXPECT_NE(decoded.status().message().find("truncated"), std::string::npos)
          << decoded.status().toString();
    }
    const auto padded = decodeRegion(bytes + '\0');
    EXPECT_NE(padded.status().message().find("1 trailing bytes"), std::string::npos)
        << padded.status().toString();
  }
}

TEST(RegionCodec, RejectsForeignBytesWrongMagicAndWrongVersion) {
  const std::string bytes = smallEncoding();
  std::string foreign = bytes;
  std::memcpy(foreign.data(), "glTF", 4);
  auto decoded = decodeRegion(foreign);
  EXPECT_EQ(decoded.status().code(), ErrorCode::kParseError);
  EXPECT_NE(decoded.status().message().find("not a Tessera region"), std::string::npos)
      << decoded.status().toString();
  // The bare Draco payload is foreign too.
  decoded = decodeRegion(bytes.substr(kRegionHeaderBytes));
  EXPECT_NE(decoded.status().message().find("not a Tessera region"), std::string::npos)
      << decoded.status().toString();
  decoded = decodeRegion(std::string(300, 'x'));
  EXPECT_NE(decoded.status().message().find("not a Tessera region"), std::string::npos)
      << decoded.status().toString();

  std::string future = bytes;
  future[4] = 3;
  refreshRegionChecksum(future);
  decoded = decodeRegion(future);
  EXPECT_EQ(decoded.status().code(), ErrorCode::kUnsupported);
  EXPECT_NE(decoded.status().message().find("format version 3"), std::string::npos)
      << decoded.status().toString();
}

TEST(RegionCodec, RejectsOversizedAndInconsistentCounts) {
  const std::string bytes = smallEncoding();
  const auto withTriangles = [&](uint32_t triangles) {
    std::string b = bytes;
    std::memcpy(b.data() + 91, &triangles, 4);
    refreshRegionChecksum(b);
    return decodeRegion(b).status();
  };
  // More triangles than the payload could hold: refused before Draco runs.
  Status status = withTriangles(0xFFFFFFFFu);
  EXPECT_NE(status.message().find("outside the accepted bounds"), std::string::npos) << status.toString();
  status = withTriangles(0);
  EXPECT_NE(status.message().find("outside the accepted bounds"), std::string::npos) << status.toString();
  // A count the payload could hold, but not the one Draco declares.
  status = withTriangles(3);
  EXPECT_NE(status.message().find("the header announces 3"), std::string::npos) << status.toString();
  // A payload size far beyond the bytes present.
  std::string b = bytes;
  const uint32_t huge = 0x7FFFFFFFu;
  std::memcpy(b.data() + 95, &huge, 4);
  status = decodeRegion(b).status();
  EXPECT_NE(status.message().find("truncated"), std::string::npos) << status.toString();
}

TEST(RegionCodec, RandomCorruptionIsAlwaysDetected) {
  // CRC-32 detects every burst of up to 32 bits and every error of up to 3
  // bits in messages of this size, so each mutation must be refused.
  const std::string bytes = smallEncoding();
  std::mt19937 rng(2024);
  for (int trial = 0; trial < 3000; ++trial) {
    std::string mutated = bytes;
    std::uniform_int_distribution<size_t> at(0, mutated.size() - 1);
    switch (trial % 4) {
      case 0:
      case 1: {  // 1..3 bit flips
        const int flips = 1 + trial % 3;
        std::set<std::pair<size_t, int>> done;
        while (static_cast<int>(done.size()) < flips) done.insert({at(rng), static_cast<int>(rng() % 8)});
        for (const auto& [byte, bit] : done) mutated[byte] = static_cast<char>(mutated[byte] ^ (1 << bit));
        break;
      }
      case 2: {  // one byte replaced
        const size_t i = at(rng);
        mutated[i] = static_cast<char>(mutated[i] ^ (1 + rng() % 255));
        break;
      }
      default:  // a byte inserted or removed
        if (rng() % 2) {
          mutated.insert(mutated.begin() + static_cast<std::ptrdiff_t>(at(rng)), static_cast<char>(rng()));
        } else {
          mutated.erase(mutated.begin() + static_cast<std::ptrdiff_t>(at(rng)));
        }
    }
    const auto decoded = decodeRegion(mutated);
    ASSERT_FALSE(decoded.isOk()) << "trial " << trial;
    EXPECT_FALSE(decoded.status().message().empty());
  }
}

TEST(RegionCodec, MutationsBehindAValidChecksumNeverCrash) {
  // The checksum recomputed after each mutation, so the header checks, the
  // Draco pre-parse and Draco's decoder all see damaged data. Each outcome
  // is an error, or a structurally valid region.
  for (int level : {0, 10}) {
    const std::string bytes = smallEncoding(level);
    const size_t payloadEnd = bytes.size() - kRegionTrailerBytes;
    std::mt19937 rng(77 + level);
    int accepted = 0;
    for (int trial = 0; trial < 2000; ++trial) {
      std::string mutated = bytes;
      const int edits = 1 + static_cast<int>(rng() % 4);
      for (int e = 0; e < edits; ++e) {
        // Half the edits hit the header and the Draco counts that follow it.
        const size_t span = rng() % 2 ? std::min<size_t>(payloadEnd, kRegionHeaderBytes + 32) : payloadEnd;
        const size_t i = rng() % span;
        mutated[i] = static_cast<char>(rng() % 3 == 0 ? rng() : mutated[i] ^ (1 << (rng() % 8)));
      }
      refreshRegionChecksum(mutated);
      const auto decoded = decodeRegion(mutated);
      if (!decoded.isOk()) {
        EXPECT_FALSE(decoded.status().message().empty());
        continue;
      }
      ++accepted;
      const auto& [header, mesh] = decoded.value();
      ASSERT_FALSE(mesh.triangles.empty());
      ASSERT_EQ(mesh.normals.size(), mesh.positions.size());
      ASSERT_EQ(mesh.vertexIds.size(), mesh.positions.size());
      for (const auto& t : mesh.triangles) {
        for (int c : t) ASSERT_TRUE(c >= 0 && static_cast<size_t>(c) < mesh.positions.size());
      }
      for (const Vec3& p : mesh.positions) ASSERT_TRUE(isFinite(p));
    }
    std::cout << "[ measured ] level " << level << ": " << accepted
              << " of 2000 mutations decoded to a valid region (e.g. a changed id or position)\n";
  }
}

}  // namespace
}  // namespace tessera
