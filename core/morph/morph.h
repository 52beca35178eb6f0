// Morphing between keys of one connectivity ("Interactively Morphing
// Irregularly Shaped Images Employing Subdivision Techniques" §5).
//
// The paper interpolates the two rough control meshes S_R0 and S_R1 into
// S_Rt and subdivides that, with the interpolated tension of the
// interpolating vertices; Kochanek-Bartels paths through the control points
// are its optional trajectory editing. Here a key is a whole Document of the
// shared base triangles, and the document at time t is:
//
//   base points    each base vertex on its path: linear between two keys,
//                  Kochanek-Bartels (tension, continuity, bias per vertex;
//                  0, 0, 0 is Catmull-Rom) through three or more;
//   base tags      each crease and corner sharpness piecewise linear in t
//                  (absent in a key: 0, smooth);
//   finer edits    each vertex's summed detail offset (in its local frame, so
//                  it follows the morphing coarse mesh, core/loop/local_frame.h)
//                  piecewise linear, absent = 0; finer sharpness tags and
//                  interpolating vertices must be on the same elements in
//                  every key, their values (sharpness, tension, tangent)
//                  piecewise linear;
//
// and is then subdivided as any document. Piecewise linear means between the
// two keys around t, so t at a key's time gives that key's values.
#pragma once

#include <cstdint>
#include <map>
#include <vector>

#include "core/document/document.h"
#include "core/util/status.h"

namespace tessera {

// Kochanek & Bartels 1984: tension tightens the path at a key, continuity
// breaks its smoothness there, bias leans it towards the previous or the
// next key. All 0: Catmull-Rom.
struct TcbParams {
  double tension = 0, continuity = 0, bias = 0;
};

// Morph keys are Loop documents (docs/INTERPOLATION.md "Morph documents in
// the service"): an error naming the key otherwise.
Status checkMorphScheme(const Document& key, const std::string& name);

// An error naming the first difference if two documents do not share their
// base triangles (the same faces, vertex for vertex, in the same order).
Status checkSameConnectivity(const BaseTopology& a, const BaseTopology& b, const std::string& nameA,
                             const std::string& nameB);

class Morph {
 public:
  // At least two keys of one connectivity and the same document options,
  // at strictly increasing times (default: evenly from 0 to 1).
  static Expected<Morph> create(std::vector<Document> keys, std::vector<double> times = {});

  size_t numKeys() const { return keys_.size(); }
  const Document& key(size_t i) const { return keys_[i]; }
  Document& key(size_t i) { return keys_[i]; }  // edits keep the connectivity
  double time(size_t i) const { return times_[i]; }

  // The path of base vertex v through three or more keys.
  Status setPath(uint32_t v, const TcbParams& params);

  // The document at time t, clamped to the keys' times.
  Expected<Document> at(double t) const;
  // Base vertex v's position at time t (the base points of at(t)).
  Vec3 pointAt(uint32_t v, double t) const;

 private:
  Morph(std::vector<Document> keys, std::vector<double> times);
  // The key segment holding t and the fraction along it.
  std::pair<size_t, double> segment(double t) const;

  std::vector<Document> keys_;
  std::vector<double> times_;
  std::map<uint32_t, TcbParams> paths_;
};

}  // namespace tessera
