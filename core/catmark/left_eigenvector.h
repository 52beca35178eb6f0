// The dominant left eigenvector of a small sparse subdivision matrix within
// a subspace, by power iteration: the exact limit and tangent masks of a
// vertex neighbourhood that one step of subdivision maps to itself
// (core/catmark/crease_span_tangent.h, core/catmark/dart_masks.h). Pure
// numbers, no mesh.
#pragma once

#include <functional>
#include <vector>

namespace tessera::catmark {

// New point `row` = sum of weight x old point `column`.
struct MatrixEntry {
  int row, column;
  double weight;
};

// Sum of x[j] y[j].
double dotOf(const std::vector<double>& x, const std::vector<double>& y);

struct LeftEigenvector {
  std::vector<double> vector;  // largest component of magnitude 1
  double eigenvalue = 0;
};

// Iterates x <- project(x S) from `start` until no component moves by
// 1e-14 (at most a million steps). `project` keeps x in the subspace
// (mirror symmetry, no constant part); it may be empty.
LeftEigenvector dominantLeftEigenvector(const std::vector<MatrixEntry>& matrix, std::vector<double> start,
                                        const std::function<void(std::vector<double>&)>& project);

}  // namespace tessera::catmark
