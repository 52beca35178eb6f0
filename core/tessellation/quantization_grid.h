// The quantization grid: the one lattice every region of a document quantizes
// its positions on before Draco compresses them (docs/REGION_ENCODING.md).
//
// Why one grid per document: Draco quantizes each position to the nearest
// point of a lattice given by an origin, a range and a bit count. When every
// region uses the same lattice (an explicit origin and range, not each
// region's own bounding box) a vertex shared by two regions lands on the same
// lattice point in both and decodes to bit-identical floats, so the union of
// separately decoded regions has no cracks (docs/REGION_ENCODING.md).
//
// The region codec (region_codec.h) states the grid in every region's header
// and checks on decoding that Draco used exactly that grid.
#pragma once

#include "core/util/status.h"
#include "core/util/vec3.h"

namespace tessera {

// The quantization lattice shared by every region of a document. Positions
// must lie in the cube [origin, origin + range]^3; each coordinate is stored
// as one of 2^positionBits evenly spaced values. origin and range must be
// float32 values because Draco stores them as float32: the header then states
// exactly what the decoder uses.
struct QuantizationGrid {
  Vec3 origin;
  double range = 1.0;
  int positionBits = 13;  // 1..24: a float32 has no finer steps to offer
  int normalBits = 10;    // octahedral quantization of normals, 2..24

  friend bool operator==(const QuantizationGrid&, const QuantizationGrid&) = default;

  // Ok when Draco can use the grid as is: finite float32 origin and range,
  // range > 0, bits in range, and float32 rounding unable to push the lattice
  // index of a point inside the grid out of [0, 2^bits - 1] (this fails for a
  // fine grid far from the origin).
  Status check() const;

  // Worst-case distance between a position inside the grid and its decoded
  // value: sqrt(3) * (step (1/2 + s) + u (2 range + M)), where
  // step = range / (2^bits - 1), u = 2^-24 (float32 rounding), M the largest
  // |coordinate| of the grid's corners and s = u 2^bits (M / range + 5) the
  // float32 error of the encoder's lattice index, in steps. Half a step is
  // Draco's rounding to the nearest lattice point; the other terms bound the
  // float32 arithmetic of Draco's quantizer and dequantizer
  // (attribute_quantization_transform.cc, quantization_utils.h).
  double maxPositionError() const;

  // Whether a position can be encoded on the grid: within [0, range] of the
  // origin on every axis (the one test the encoder and servers share).
  bool contains(const Vec3& p) const {
    for (int k = 0; k < 3; ++k) {
      const double t = p[k] - origin[k];
      if (!(t >= 0.0 && t <= range)) return false;
    }
    return true;
  }
};

inline constexpr double kDefaultMaxErrorFraction = 1e-4;  // of the bbox diagonal (docs/REGION_ENCODING.md)
// Each side of the bounding box is moved out by this fraction of its
// diagonal, so edits that move the surface a little keep it inside the grid;
// when it leaves anyway, encodeRegion says so and the document needs a new
// grid (and a full re-encode).
inline constexpr double kGridPaddingFraction = 0.1;
inline constexpr int kDefaultNormalBits = 10;

// The grid for a document whose surface lies in [bboxMin, bboxMax]: the box
// padded by kGridPaddingFraction of its diagonal D, origin rounded down and
// range rounded up to float32, and the smallest positionBits with
// maxPositionError() <= maxErrorFraction * D (13 bits for a cube at 1e-4).
// normalBits is kDefaultNormalBits. Errors: a non-finite or inverted box, a
// zero diagonal, a fraction outside (0, 1), or a box so far from the origin
// relative to its size that float32 cannot reach the precision.
Expected<QuantizationGrid> gridFor(const Vec3& bboxMin, const Vec3& bboxMax,
                                   double maxErrorFraction = kDefaultMaxErrorFraction);

}  // namespace tessera
