#include "client/replay/camera_path.h"

#include <cmath>
#include <numbers>
#include <random>

namespace tessera::replay {

namespace {

constexpr double kPi = std::numbers::pi;

// The viewer's own numbers, the same at every call.
struct Draw {
  double phase, elevation, distance, a, b, c;
};

Draw drawFor(const CameraPaths& p, int viewer, uint64_t step = 0) {
  std::mt19937_64 rng(p.seed * 0x9E3779B97F4A7C15ull + static_cast<uint64_t>(viewer) * 7919 + step * 104729);
  std::uniform_real_distribution<double> unit(0, 1);
  Draw d{};
  d.phase = 2 * kPi * unit(rng);
  d.elevation = (unit(rng) - 0.5) * 1.2;
  d.distance = 1.5 + 1.5 * unit(rng);
  d.a = unit(rng), d.b = unit(rng), d.c = unit(rng);
  return d;
}

Vec3 direction(double azimuth, double elevation) {
  return {std::cos(azimuth) * std::cos(elevation), std::sin(elevation),
          std::sin(azimuth) * std::cos(elevation)};
}

View looking(const CameraPaths& p, const Vec3& eye, const Vec3& target) {
  View v;
  v.eye = eye;
  v.forward = target - eye;
  v.up = std::abs(v.forward.normalized()[1]) > 0.95 ? Vec3(1, 0, 0) : Vec3(0, 1, 0);
  v.fovYRadians = 50 * kPi / 180;
  v.nearDistance = p.radius * 1e-3;
  v.width = p.width;
  v.height = p.height;
  v.tolerancePixels = p.tolerancePixels;
  return v;
}

}  // namespace

Expected<CameraPathKind> cameraPathKind(const std::string& name) {
  if (name == "orbit") return CameraPathKind::kOrbit;
  if (name == "zoom") return CameraPathKind::kZoom;
  if (name == "fly") return CameraPathKind::kFly;
  if (name == "random") return CameraPathKind::kRandom;
  return invalidArgument("--cameras: expects orbit, zoom, fly or random, got '" + name + "'");
}

const char* cameraPathName(CameraPathKind kind) {
  switch (kind) {
    case CameraPathKind::kOrbit:
      return "orbit";
    case CameraPathKind::kZoom:
      return "zoom";
    case CameraPathKind::kFly:
      return "fly";
    case CameraPathKind::kRandom:
      return "random";
  }
  return "?";
}

View cameraAt(const CameraPaths& p, int viewer, double seconds) {
  const Draw d = drawFor(p, viewer);
  switch (p.kind) {
    case CameraPathKind::kOrbit: {
      const double azimuth = d.phase + 2 * kPi * seconds / 20;
      return looking(p, p.centre + d.distance * p.radius * direction(azimuth, d.elevation), p.centre);
    }
    case CameraPathKind::kZoom: {
      const double s = 0.5 + 0.5 * std::cos(2 * kPi * seconds / 10 + d.phase);  // 1: far, 0: near
      const double distance = p.radius * (0.3 + 2.7 * s);
      return looking(p, p.centre + distance * direction(d.phase, d.elevation), p.centre);
    }
    case CameraPathKind::kFly: {
      // A line through the sphere at up to half a radius from its centre.
      const Vec3 along = direction(d.phase, d.elevation);
      const Vec3 side = direction(d.phase + kPi / 2, 0);
      const Vec3 offset = 0.5 * p.radius * (d.a - 0.5) * side + 0.5 * p.radius * (d.b - 0.5) * Vec3(0, 1, 0);
      const double u = std::fmod(seconds / 10 + d.c, 1.0);  // 0..1 along the line
      const Vec3 eye = p.centre + offset + (3 * u - 1.5) * p.radius * along;
      return looking(p, eye, eye + along);
    }
    case CameraPathKind::kRandom: {
      const Draw j = drawFor(p, viewer, static_cast<uint64_t>(std::max(0.0, seconds)) + 1);
      const Vec3 target = p.centre + 0.4 * p.radius * Vec3(j.a - 0.5, j.b - 0.5, j.c - 0.5);
      return looking(p, p.centre + j.distance * p.radius * direction(j.phase, j.elevation), target);
    }
  }
  return looking(p, p.centre + Vec3(0, 0, 3 * p.radius), p.centre);
}

}  // namespace tessera::replay
