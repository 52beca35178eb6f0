// PNG pictures the viewer wrote, read back for the screenshot tests, and
// the pixel measures they check: what differs from the background, where
// two pictures differ, and how far silhouette pixels blend into the
// background (anti-aliasing).
#pragma once

#include <stb_image.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <optional>
#include <string>
#include <vector>

namespace tessera::testing {

using Rgb = std::array<int, 3>;

struct Image {
  int width = 0, height = 0;
  std::vector<unsigned char> rgb;
  Rgb at(int x, int y) const {
    const size_t i = (static_cast<size_t>(y) * width + x) * 3;
    return {rgb[i], rgb[i + 1], rgb[i + 2]};
  }
};

inline std::optional<Image> readPng(const std::string& path) {
  int w = 0, h = 0, channels = 0;
  unsigned char* data = stbi_load(path.c_str(), &w, &h, &channels, 3);
  if (!data) return std::nullopt;
  Image image{w, h, std::vector<unsigned char>(data, data + static_cast<size_t>(w) * h * 3)};
  stbi_image_free(data);
  return image;
}

inline bool differ(Rgb a, Rgb b, int tolerance = 8) {
  return std::abs(a[0] - b[0]) > tolerance || std::abs(a[1] - b[1]) > tolerance ||
         std::abs(a[2] - b[2]) > tolerance;
}

inline int distance(Rgb a, Rgb b) {
  return std::abs(a[0] - b[0]) + std::abs(a[1] - b[1]) + std::abs(a[2] - b[2]);
}

inline double luminance(Rgb c) {
  return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
}

// A pixel box, `x1` and `y1` included; empty when x0 > x1.
struct Box {
  int x0 = 1 << 30, y0 = 1 << 30, x1 = -1, y1 = -1;
  bool empty() const { return x0 > x1; }
  void add(int x, int y) {
    x0 = std::min(x0, x), y0 = std::min(y0, y), x1 = std::max(x1, x), y1 = std::max(y1, y);
  }
  bool contains(int x, int y) const { return x >= x0 && x <= x1 && y >= y0 && y <= y1; }
  int width() const { return empty() ? 0 : x1 - x0 + 1; }
  int height() const { return empty() ? 0 : y1 - y0 + 1; }
};

// The pixels of `a` unlike `b`'s (the same size): their box and count.
struct Difference {
  Box box;
  size_t pixels = 0;
};
inline Difference difference(const Image& a, const Image& b, int tolerance = 8) {
  Difference d;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x)
      if (differ(a.at(x, y), b.at(x, y), tolerance)) d.box.add(x, y), ++d.pixels;
  return d;
}

// The pixels unlike the background colour `bg`.
inline Difference foreground(const Image& a, Rgb bg, int tolerance = 8) {
  Difference d;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x)
      if (differ(a.at(x, y), bg, tolerance)) d.box.add(x, y), ++d.pixels;
  return d;
}

// Silhouette pixels: not the background, with the background for two
// pixels on the left or the right (not a one-pixel crack) and, two and three
// pixels the other way, surface of one even shade. A blended pixel is a mix
// of the two: its colour lies on the segment from the background to that
// shade (within 10 units), at a fraction t with 0.1 < t < 0.9. With no
// anti-aliasing a silhouette pixel is wholly surface, or a dark back face
// seen at a grazing angle, which is no mix; with multisampling many are
// partly covered. Returns how many silhouette pixels there are and how many
// are blended.
struct Silhouette {
  size_t pixels = 0, blended = 0;
};
inline Silhouette silhouette(const Image& a, Rgb bg) {
  Silhouette s;
  auto isBackground = [&](int x, int y) { return distance(a.at(x, y), bg) <= 3; };
  for (int y = 0; y < a.height; ++y) {
    for (int x = 4; x + 4 < a.width; ++x) {
      if (isBackground(x, y)) continue;
      for (int side : {-1, 1}) {
        if (!isBackground(x + side, y) || !isBackground(x + 2 * side, y)) continue;
        const int ix = x - 2 * side;
        const Rgb inner = a.at(ix, y);
        if (isBackground(ix, y) || distance(inner, a.at(ix - side, y)) > 12) continue;
        if (distance(inner, bg) < 60) continue;  // too close to the background to measure a blend
        const Rgb c = a.at(x, y);
        double along = 0, length2 = 0;
        for (int k = 0; k < 3; ++k) {
          along += (c[k] - bg[k]) * (inner[k] - bg[k]);
          length2 += (inner[k] - bg[k]) * (inner[k] - bg[k]);
        }
        const double t = along / length2;
        double off = 0;
        for (int k = 0; k < 3; ++k) {
          const double e = c[k] - (bg[k] + t * (inner[k] - bg[k]));
          off += e * e;
        }
        ++s.pixels;
        if (t > 0.1 && t < 0.9 && off < 100) ++s.blended;
        break;
      }
    }
  }
  return s;
}

}  // namespace tessera::testing
