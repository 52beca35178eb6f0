#include "core/loop/limit_masks.h"

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cassert>
#include <cmath>
#include <map>
#include <mutex>
#include <numeric>
#include <shared_mutex>

#include "core/loop/masks.h"

namespace tessera {

namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;

// Eigenvalues closer than this count as one (the matrices hold dyadic
// rationals and cosines; distinct eigenvalues differ by far more).
constexpr double kTie = 1e-9;

std::vector<int> sharpPositions(const StationaryRing& ring) {
  std::vector<int> sharp;
  for (int k = 0; k < ring.valence; ++k) {
    if (ring.sharpEdges[k]) sharp.push_back(k);
  }
  return sharp;
}

MatrixXd subdivisionMatrix(const StationaryRing& ring) {
  const int n = ring.valence;
  MatrixXd s = MatrixXd::Zero(n + 1, n + 1);
  switch (ring.rule) {
    case VertexRule::kSmooth:
    case VertexRule::kDart: {
      const double w = loop::smoothEdgeWeight(n);
      s(0, 0) = 1.0 - n * w;
      for (int k = 0; k < n; ++k) s(0, 1 + k) = w;
      break;
    }
    case VertexRule::kCrease: {
      const std::vector<int> sharp = sharpPositions(ring);
      assert(sharp.size() == 2);
      s(0, 0) = loop::kCreaseVertexWeight;
      s(0, 1 + sharp[0]) = loop::kCreaseNeighbourWeight;
      s(0, 1 + sharp[1]) = loop::kCreaseNeighbourWeight;
      break;
    }
    case VertexRule::kCorner:
      s(0, 0) = 1.0;
      break;
  }
  for (int k = 0; k < n; ++k) {
    if (ring.sharpEdges[k]) {
      s(1 + k, 0) = s(1 + k, 1 + k) = 0.5;
      continue;
    }
    s(1 + k, 0) = s(1 + k, 1 + k) = loop::kEdgeEndWeight;
    s(1 + k, 1 + (k + n - 1) % n) += loop::kEdgeOppositeWeight;
    s(1 + k, 1 + (k + 1) % n) += loop::kEdgeOppositeWeight;
  }
  return s;
}

// The left eigenvector of eigenvalue 1, scaled so the weights sum to 1 (the
// right eigenvector is all ones: every row sums to 1).
std::vector<double> positionMask(const MatrixXd& s) {
  Eigen::EigenSolver<MatrixXd> left(s.transpose());
  int best = 0;
  for (int i = 1; i < left.eigenvalues().size(); ++i) {
    if (std::abs(left.eigenvalues()[i] - 1.0) < std::abs(left.eigenvalues()[best] - 1.0)) best = i;
  }
  const VectorXd l = left.eigenvectors().col(best).real();
  const double sum = l.sum();
  std::vector<double> mask(l.size());
  for (int i = 0; i < l.size(); ++i) mask[i] = l[i] / sum;
  return mask;
}

struct Sector {
  int firstEdge = 0;
  int faceCount = 0;
  std::vector<int> points;  // indices into the ring matrix: 0, then the ring from firstEdge on
  bool bounded = false;     // between two sharp edges (else the whole interior ring)
};

std::vector<Sector> sectorsOf(const StationaryRing& ring) {
  const int n = ring.valence;
  const std::vector<int> sharp = sharpPositions(ring);
  const int m = static_cast<int>(sharp.size());
  std::vector<Sector> sectors;
  const bool bounded = (ring.rule == VertexRule::kCrease || ring.rule == VertexRule::kCorner) && m >= 2;
  if (!bounded) {
    Sector whole{0, n, {0}, false};
    for (int k = 0; k < n; ++k) whole.points.push_back(1 + k);
    sectors.push_back(whole);
    return sectors;
  }
  for (int i = 0; i < m; ++i) {
    const bool wraps = i + 1 == m;
    if (wraps && ring.boundary) continue;  // no faces past the last boundary edge
    const int from = sharp[i];
    const int to = wraps ? sharp[0] + n : sharp[i + 1];
    Sector sector{from, to - from, {0}, true};
    for (int k = from; k <= to; ++k) sector.points.push_back(1 + k % n);
    sectors.push_back(sector);
  }
  return sectors;
}

// The leading subdominant pair of a sector's matrix, if it singles out a
// tangent plane: left eigenvectors L (2 x size) and right eigenvectors R
// (size x 2) with L R = I.
struct Pair {
  MatrixXd left, right;
  double lambda1 = 0, lambda2 = 0;
};

struct Spectrum {
  std::vector<std::complex<double>> values;
  std::vector<int> order;  // by real part, descending
  Eigen::EigenSolver<MatrixXd> left, right;
};

Spectrum spectrumOf(const MatrixXd& a) {
  Spectrum sp;
  sp.left.compute(a.transpose());
  sp.right.compute(a);
  for (int i = 0; i < a.rows(); ++i) sp.values.push_back(sp.left.eigenvalues()[i]);
  sp.order.resize(a.rows());
  std::iota(sp.order.begin(), sp.order.end(), 0);
  std::sort(sp.order.begin(), sp.order.end(),
            [&](int x, int y) { return sp.values[x].real() > sp.values[y].real(); });
  return sp;
}

// Right eigenvectors of `a` for the eigenvalues of the left ones chosen.
MatrixXd matchingRight(const Spectrum& sp, const std::vector<int>& chosen) {
  std::vector<bool> used(sp.values.size(), false);
  MatrixXd r(sp.values.size(), chosen.size());
  for (size_t c = 0; c < chosen.size(); ++c) {
    const double target = sp.values[chosen[c]].real();
    int best = -1;
    for (int i = 0; i < static_cast<int>(sp.values.size()); ++i) {
      if (used[i]) continue;
      if (best < 0 || std::abs(sp.right.eigenvalues()[i].real() - target) <
                          std::abs(sp.right.eigenvalues()[best].real() - target)) {
        best = i;
      }
    }
    used[best] = true;
    r.col(c) = sp.right.eigenvectors().col(best).real();
  }
  return r;
}

// Groups the eigenvalues after the first (which is 1) into ties.
std::vector<std::vector<int>> subdominantGroups(const Spectrum& sp) {
  std::vector<std::vector<int>> groups;
  for (size_t i = 1; i < sp.order.size(); ++i) {
    const int idx = sp.order[i];
    if (!groups.empty() && std::abs(sp.values[groups.back().front()].real() - sp.values[idx].real()) < kTie) {
      groups.back().push_back(idx);
    } else {
      groups.push_back({idx});
    }
  }
  return groups;
}

bool leadingPair(const Spectrum& sp, Pair& pair) {
  const auto groups = subdominantGroups(sp);
  std::vector<int> chosen;
  if (groups.size() >= 1 && groups[0].size() == 2) {
    chosen = groups[0];
  } else if (groups.size() >= 2 && groups[0].size() == 1 && groups[1].size() == 1) {
    chosen = {groups[0][0], groups[1][0]};
  } else {
    return false;
  }
  for (int c : chosen) {
    if (std::abs(sp.values[c].imag()) > kTie || sp.values[c].real() <= 0.0) return false;
  }
  MatrixXd l(2, sp.values.size());
  l.row(0) = sp.left.eigenvectors().col(chosen[0]).real().transpose();
  l.row(1) = sp.left.eigenvectors().col(chosen[1]).real().transpose();
  const MatrixXd r0 = matchingRight(sp, chosen);
  const MatrixXd c = l * r0;
  if (std::abs(c.determinant()) < 1e-12 * l.norm() * r0.norm()) return false;  // defective
  pair.left = l;
  pair.right = r0 * c.inverse();
  pair.lambda1 = sp.values[chosen[0]].real();
  pair.lambda2 = sp.values[chosen[1]].real();
  return true;
}

// Twice the signed area of the polygon of the rows `poly` of r, read as
// points (r(i,0), r(i,1)): the orientation of the characteristic map.
double signedArea(const MatrixXd& r, const std::vector<int>& poly) {
  double area = 0.0;
  for (size_t i = 0; i < poly.size(); ++i) {
    const int a = poly[i], b = poly[(i + 1) % poly.size()];
    area += r(a, 0) * r(b, 1) - r(b, 0) * r(a, 1);
  }
  return area;
}

std::vector<double> spread(const VectorXd& local, const Sector& sector, int size) {
  std::vector<double> mask(size, 0.0);
  for (size_t i = 0; i < sector.points.size(); ++i) mask[sector.points[i]] += local[i];
  return mask;
}

SectorMasks analyseSector(const MatrixXd& s, const StationaryRing& ring, const Sector& sector) {
  const int size = static_cast<int>(sector.points.size());
  MatrixXd a(size, size);
  for (int i = 0; i < size; ++i) {
    for (int j = 0; j < size; ++j) a(i, j) = s(sector.points[i], sector.points[j]);
    assert(std::abs(a.row(i).sum() - 1.0) < 1e-12 && "a sector's rows read only the sector");
  }
  SectorMasks out;
  out.firstEdge = sector.firstEdge;
  out.faceCount = sector.faceCount;
  const Spectrum sp = spectrumOf(a);
  Pair pair;
  bool plane = leadingPair(sp, pair);
  // Local rows of the sector's sharp neighbours: the crease curves through
  // the vertex lie on the surface, so a tangent plane must hold their
  // tangents, i.e. the characteristic map must not send them to the origin.
  std::vector<int> sharpRows;
  for (int i = 1; i < size; ++i) {
    if (ring.sharpEdges[sector.points[i] - 1]) sharpRows.push_back(i);
  }
  if (plane) {
    const double scale = pair.right.norm();
    for (int i : sharpRows) {
      if (pair.right.row(i).norm() < 1e-9 * scale) plane = false;
    }
  }
  if (plane) {
    // The polygon around the vertex: the ring for a whole interior ring,
    // the wedge (vertex, first .. last neighbour) for a bounded sector.
    std::vector<int> poly;
    for (int i = sector.bounded ? 0 : 1; i < size; ++i) poly.push_back(i);
    const double area = signedArea(pair.right, poly);
    if (std::abs(area) < 1e-12 * pair.right.squaredNorm()) plane = false;
    if (plane) {
      const double sign = area > 0 ? 1.0 : -1.0;
      out.kind = SectorMasks::Kind::kTangentPlane;
      out.tangent1 = spread(pair.left.row(0).transpose(), sector, ring.valence + 1);
      out.tangent2 = spread(sign * pair.left.row(1).transpose(), sector, ring.valence + 1);
      out.lambda1 = pair.lambda1;
      out.lambda2 = pair.lambda2;
      return out;
    }
  }
  const int n = ring.valence;
  if (!sector.bounded) {
    const int dominant = sp.order[1];
    out.kind = SectorMasks::Kind::kConeAxis;
    out.tangent1 = spread(sp.left.eigenvectors().col(dominant).real(), sector, n + 1);
    out.tangent2.assign(n + 1, 0.0);
    out.lambda1 = out.lambda2 = sp.values[dominant].real();
    return out;
  }
  const int from = 1 + sector.firstEdge % n;
  const int to = 1 + (sector.firstEdge + sector.faceCount) % n;
  out.tangent1.assign(n + 1, 0.0);
  out.tangent2.assign(n + 1, 0.0);
  if (ring.rule == VertexRule::kCrease) {
    // Along the crease from the last to the first neighbour, and the
    // dominant eigenvector, signed so its right eigenvector is positive
    // inside the sector (the first sine mode of the sector's interior).
    out.kind = SectorMasks::Kind::kDominantAndCrease;
    out.tangent1[from] = 1.0;
    out.tangent1[to] = -1.0;
    const int dominant = sp.order[1];
    const VectorXd l = sp.left.eigenvectors().col(dominant).real();
    const VectorXd r = matchingRight(sp, {dominant}).col(0);
    double inside = 0.0;
    for (int i = 2; i + 1 < size; ++i) inside += r[i];
    const double sign = (inside * l.dot(r)) >= 0 ? 1.0 : -1.0;
    out.tangent2 = spread(sign * l, sector, n + 1);
    out.lambda1 = 0.5;
    out.lambda2 = sp.values[dominant].real();
    return out;
  }
  out.kind = SectorMasks::Kind::kBoundingCurves;
  out.tangent1[0] = out.tangent2[0] = -1.0;
  out.tangent1[from] = 1.0;
  out.tangent2[to] = 1.0;
  out.lambda1 = out.lambda2 = 0.5;
  return out;
}

// Cache key: valence, boundary, rule and the sharp edges.
using Key = std::vector<int>;

Key keyOf(const StationaryRing& ring) {
  Key key{ring.valence, ring.boundary ? 1 : 0, static_cast<int>(ring.rule)};
  for (bool sharp : ring.sharpEdges) key.push_back(sharp ? 1 : 0);
  return key;
}

}  // namespace

std::vector<double> stationarySubdivisionMatrix(const StationaryRing& ring) {
  const MatrixXd s = subdivisionMatrix(ring);
  std::vector<double> out;
  for (int i = 0; i < s.rows(); ++i) {
    for (int j = 0; j < s.cols(); ++j) out.push_back(s(i, j));
  }
  return out;
}

StationaryMasks computeStationaryMasks(const StationaryRing& ring) {
  const MatrixXd s = subdivisionMatrix(ring);
  StationaryMasks masks;
  masks.position = positionMask(s);
  for (const Sector& sector : sectorsOf(ring)) masks.sectors.push_back(analyseSector(s, ring, sector));
  return masks;
}

std::shared_ptr<const StationaryMasks> stationaryMasks(const StationaryRing& ring, bool* cached) {
  static std::shared_mutex mutex;
  static std::map<Key, std::shared_ptr<const StationaryMasks>> cache;
  const Key key = keyOf(ring);
  if (cached != nullptr) *cached = true;
  {
    std::shared_lock lock(mutex);
    auto it = cache.find(key);
    if (it != cache.end()) return it->second;
  }
  auto masks = std::make_shared<const StationaryMasks>(computeStationaryMasks(ring));
  std::unique_lock lock(mutex);
  if (cache.size() >= kStationaryMasksCacheEntries && !cache.contains(key)) {
    // Full: documents keep sending new configurations. Answer without
    // keeping it, so memory stays bounded.
    if (cached != nullptr) *cached = false;
    return masks;
  }
  return cache.emplace(key, std::move(masks)).first->second;
}

}  // namespace tessera
