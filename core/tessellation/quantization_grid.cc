#include "core/tessellation/quantization_grid.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>
#include <string>

#include "core/tessellation/float_text.h"

namespace tessera {
namespace {

constexpr double kFloatRounding = 0x1p-24;  // unit roundoff of float32
constexpr int kMaxPositionBits = 24;        // float32 significand
constexpr int kMinNormalBits = 2;           // the octahedral square needs a centre
constexpr int kMaxNormalBits = 24;

bool isFloat32(double x) {
  return std::isfinite(x) && std::fabs(x) <= FLT_MAX && static_cast<double>(static_cast<float>(x)) == x;
}

// Nearest float32 at or below (above) x; x must be within float32 range.
double floatDown(double x) {
  float f = static_cast<float>(x);
  if (static_cast<double>(f) > x) f = std::nextafter(f, -std::numeric_limits<float>::infinity());
  return f;
}
double floatUp(double x) {
  float f = static_cast<float>(x);
  if (static_cast<double>(f) < x) f = std::nextafter(f, std::numeric_limits<float>::infinity());
  return f;
}

uint32_t maxQuantized(int bits) {
  return (uint32_t{1} << bits) - 1;
}

// The largest |coordinate| of the grid's corners: float32 rounding is
// relative to it.
double largestCoordinate(const QuantizationGrid& grid) {
  double m = 0.0;
  for (int k = 0; k < 3; ++k)
    m = std::max({m, std::fabs(grid.origin[k]), std::fabs(grid.origin[k] + grid.range)});
  return m;
}

// How far, in steps, float32 rounding can move the encoder's lattice index
// (value - origin) * (2^bits - 1) / range + 1/2 before Draco floors it
// (Quantizer in draco/core/quantization_utils.h): the conversion of the
// value to float errs by u M, the subtraction by u range, the reciprocal and
// the product by u each relative to the index, the + 1/2 by u 2^bits. In
// steps that is at most u 2^bits (M / range + 4); 5 leaves a margin.
double indexSlack(const QuantizationGrid& grid) {
  return kFloatRounding * std::ldexp(1.0, grid.positionBits) * (largestCoordinate(grid) / grid.range + 5.0);
}

// Under this slack the floored index of any point inside the grid stays in
// [0, 2^bits - 1], which Draco's coders assume (an index moves out only when
// the slack reaches half a step); the rest is margin.
constexpr double kMaxIndexSlack = 0.45;

}  // namespace

Status QuantizationGrid::check() const {
  for (int k = 0; k < 3; ++k) {
    if (!isFloat32(origin[k])) {
      return invalidArgument(
          "quantization grid: origin " + pointText(origin) +
          " is not made of finite float32 values (Draco stores it as float32; use gridFor)");
    }
  }
  if (!isFloat32(range) || range <= 0.0 || !(largestCoordinate(*this) < FLT_MAX / 2)) {
    return invalidArgument("quantization grid: range " + floatText(range) +
                           " must be a positive float32 value with origin + range within float32");
  }
  if (positionBits < 1 || positionBits > kMaxPositionBits) {
    return invalidArgument("quantization grid: positionBits " + std::to_string(positionBits) +
                           " outside [1, " + std::to_string(kMaxPositionBits) + "]");
  }
  if (normalBits < kMinNormalBits || normalBits > kMaxNormalBits) {
    return invalidArgument("quantization grid: normalBits " + std::to_string(normalBits) + " outside [" +
                           std::to_string(kMinNormalBits) + ", " + std::to_string(kMaxNormalBits) + "]");
  }
  if (indexSlack(*this) > kMaxIndexSlack) {
    return invalidArgument("quantization grid: " + std::to_string(positionBits) + " bits over a range of " +
                           floatText(range) + " at " + floatText(largestCoordinate(*this)) +
                           " from the origin are finer than float32 resolves there");
  }
  return Status::ok();
}

double QuantizationGrid::maxPositionError() const {
  const double step = range / maxQuantized(positionBits);
  // Encoding: half a step of rounding plus the index slack. Decoding
  // (Dequantizer, then + origin) errs by u 2 range for the product and u M for
  // the sum; 1.001 covers the second-order terms.
  const double decoding = 1.001 * kFloatRounding * (2.0 * range + largestCoordinate(*this));
  const double perAxis = step * (0.5 + indexSlack(*this)) + decoding;
  return std::sqrt(3.0) * perAxis;
}

Expected<QuantizationGrid> gridFor(const Vec3& bboxMin, const Vec3& bboxMax, double maxErrorFraction) {
  const std::string box = "bounding box " + pointText(bboxMin) + " .. " + pointText(bboxMax);
  if (!isFinite(bboxMin) || !isFinite(bboxMax)) return invalidArgument("gridFor: " + box + " is not finite");
  for (int k = 0; k < 3; ++k) {
    if (bboxMin[k] > bboxMax[k])
      return invalidArgument("gridFor: " + box + " has min > max on axis " + std::to_string(k));
  }
  if (!(maxErrorFraction > 0.0 && maxErrorFraction < 1.0)) {
    return invalidArgument("gridFor: maxErrorFraction " + floatText(maxErrorFraction) + " outside (0, 1)");
  }
  const double diagonal = (bboxMax - bboxMin).norm();
  if (!(diagonal > 0.0))
    return invalidArgument("gridFor: " + box + " is a single point: no size to relate an error to");
  const double pad = kGridPaddingFraction * diagonal;
  double magnitude = 0.0;
  for (int k = 0; k < 3; ++k) magnitude = std::max({magnitude, std::fabs(bboxMin[k]), std::fabs(bboxMax[k])});
  if (!(magnitude + 2.0 * diagonal < FLT_MAX / 4)) {
    return invalidArgument("gridFor: " + box + " exceeds the float32 range Draco stores positions in");
  }

  QuantizationGrid grid;
  grid.normalBits = kDefaultNormalBits;
  double extent = 0.0;
  for (int k = 0; k < 3; ++k) {
    grid.origin[k] = floatDown(bboxMin[k] - pad);
    extent = std::max(extent, bboxMax[k] + pad - grid.origin[k]);
  }
  grid.range = floatUp(extent);
  const double target = maxErrorFraction * diagonal;
  for (int bits = 1; bits <= kMaxPositionBits; ++bits) {
    grid.positionBits = bits;
    if (indexSlack(grid) <= kMaxIndexSlack && grid.maxPositionError() <= target) return grid;
  }
  return invalidArgument("gridFor: " + box + ": no position bits up to " + std::to_string(kMaxPositionBits) +
                         " reach an error of " + floatText(target) +
                         ": the box is too far from the origin for its size " + "to be quantized in float32");
}

}  // namespace tessera
