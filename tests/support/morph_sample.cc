#include "support/morph_sample.h"

#include <cmath>
#include <filesystem>
#include <fstream>

namespace tessera::testing {

namespace {

constexpr int kWidth = 160, kHeight = 120;
constexpr int kSegments = 12;                     // around the ring
constexpr double kRadii[3] = {18.0, 32.0, 46.0};  // hole, middle, outline

// Mesh A's vertex (ring r, segment s); B is an affine image of A.
Vec3 ringPoint(int r, int s) {
  const double angle = 2 * M_PI * s / kSegments;
  return Vec3(70 + kRadii[r] * std::cos(angle), 60 + kRadii[r] * std::sin(angle), 0);
}

Vec3 affine(const Vec3& p, bool mirrored) {
  const double c = std::cos(0.35), s = std::sin(0.35);
  const double x = (p[0] - 70) * 1.15, y = (p[1] - 60) * 0.8;
  const double mx = mirrored ? -x : x;
  return Vec3(92 + c * mx - s * y, 58 + s * mx + c * y, 0);
}

void fill(Image& image, int x, int y, uint8_t r, uint8_t g, uint8_t b) {
  if (x < 0 || y < 0 || x >= image.width || y >= image.height) return;
  uint8_t* p = image.at(x, y);
  p[0] = r, p[1] = g, p[2] = b, p[3] = 255;
}

// A striped ring around `centre` through `to` (pixel -> where it is in mesh
// A's frame), so that the stripes follow the shape; background elsewhere.
template <typename ToA>
Image ringImage(const std::array<uint8_t, 3>& background, const std::array<uint8_t, 3>& stripe, ToA toA) {
  Image image{kWidth, kHeight, std::vector<uint8_t>(kWidth * kHeight * 4)};
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      const Vec3 p = toA(Vec3(x + 0.5, y + 0.5, 0));
      const double dx = p[0] - 70, dy = p[1] - 60, r = std::hypot(dx, dy);
      if (r < kRadii[0] - 1 || r > kRadii[2] - 4) {
        fill(image, x, y, background[0], background[1], background[2]);
        continue;
      }
      const double angle = std::atan2(dy, dx);
      const bool dark = std::fmod(angle + 4 * M_PI, 2 * M_PI / 16) < M_PI / 16;
      const double shade = 0.6 + 0.4 * (r - kRadii[0]) / (kRadii[2] - kRadii[0]);
      fill(image, x, y, static_cast<uint8_t>(stripe[0] * shade * (dark ? 0.55 : 1)),
           static_cast<uint8_t>(stripe[1] * shade * (dark ? 0.55 : 1)),
           static_cast<uint8_t>(stripe[2] * shade));
    }
  }
  return image;
}

void dot(Image& image, const Vec3& centre) {
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      fill(image, static_cast<int>(std::floor(centre[0])) + dx, static_cast<int>(std::floor(centre[1])) + dy,
           0, 255, 0);
    }
  }
}

}  // namespace

MorphSample makeMorphSample(bool mirrored) {
  MorphSample s;
  auto index = [](int r, int seg) { return r * kSegments + (seg % kSegments); };
  for (int r = 0; r < 3; ++r) {
    for (int seg = 0; seg < kSegments; ++seg) {
      s.meshA.push_back(ringPoint(r, seg));
      s.meshB.push_back(affine(ringPoint(r, seg), mirrored));
    }
  }
  // Counter-clockwise in mesh A's (x, y) as drawn with y down.
  for (int r = 0; r < 2; ++r) {
    for (int seg = 0; seg < kSegments; ++seg) {
      const int a = index(r, seg), b = index(r, seg + 1), c = index(r + 1, seg), d = index(r + 1, seg + 1);
      s.triangles.push_back({a, b, d});
      s.triangles.push_back({a, d, c});
    }
  }
  s.interpolating = {index(1, 0), index(1, 4), index(1, 8)};
  s.dotVertex = index(1, 0);
  s.holeA = Vec3(70, 60, 0);
  s.holeB = affine(s.holeA, mirrored);
  // Image B: the ring mapped by the same affine map (inverted per pixel).
  const double c = std::cos(0.35), sn = std::sin(0.35);
  auto fromB = [&](const Vec3& q) {
    const double u = q[0] - 92, v = q[1] - 58;
    const double mx = c * u + sn * v, y = -sn * u + c * v;
    const double x = mirrored ? -mx : mx;
    return Vec3(70 + x / 1.15, 60 + y / 0.8, 0);
  };
  s.a = ringImage({200, 225, 245}, {230, 90, 40}, [](const Vec3& p) { return p; });
  s.b = ringImage({250, 240, 190}, {60, 80, 220}, fromB);
  dot(s.a, s.meshA[s.dotVertex]);
  dot(s.b, s.meshB[s.dotVertex]);
  return s;
}

Status writeMorphSample(const MorphSample& s, const std::string& dir) {
  std::filesystem::create_directories(dir);
  TESSERA_RETURN_IF_ERROR(writePng(dir + "/a.png", s.a));
  TESSERA_RETURN_IF_ERROR(writePng(dir + "/b.png", s.b));
  for (const auto& [name, points] : {std::pair{"mesh_a.obj", &s.meshA}, std::pair{"mesh_b.obj", &s.meshB}}) {
    std::ofstream out(dir + "/" + name);
    out << "# annulus in pixel coordinates of " << (points == &s.meshA ? "a.png" : "b.png") << "\n";
    out.precision(17);
    for (const Vec3& p : *points) out << "v " << p[0] << " " << p[1] << " 0\n";
    for (const auto& t : s.triangles) out << "f " << t[0] + 1 << " " << t[1] + 1 << " " << t[2] + 1 << "\n";
    if (!out) return ioError(dir + "/" + name + ": cannot write");
  }
  std::ofstream tags(dir + "/morph.tags");
  tags << "# the middle ring's segments 0, 4 and 8 (vertices " << s.interpolating[0] << ", "
       << s.interpolating[1] << " and " << s.interpolating[2]
       << ") interpolate (docs/INTERPOLATION.md, \"Locally interpolating vertices\"); the dots mark vertex "
       << s.dotVertex << "\n";
  for (int v : s.interpolating) tags << "interpolate " << v << "\n";
  if (!tags) return ioError(dir + "/morph.tags: cannot write");
  return Status::ok();
}

}  // namespace tessera::testing
