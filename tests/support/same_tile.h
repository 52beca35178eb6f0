// Two tiles of one document equal bit for bit: mesh, triangle count and
// bounds (core/view/tile_catalogue.h). For tests that build a tile two ways.
#pragma once

#include <gtest/gtest.h>

#include <string>

#include "core/view/tile_catalogue.h"

namespace tessera::testing {

inline void expectSameTile(const Tile& a, const Tile& b, const std::string& where) {
  ASSERT_EQ(a.mesh.positions.size(), b.mesh.positions.size()) << where;
  for (size_t i = 0; i < a.mesh.positions.size(); ++i) {
    ASSERT_EQ(a.mesh.positions[i], b.mesh.positions[i]) << where << " vertex " << i;
    ASSERT_EQ(a.mesh.normals[i], b.mesh.normals[i]) << where << " vertex " << i;
  }
  EXPECT_EQ(a.triangles, b.triangles) << where;
  EXPECT_EQ(a.bounds.error, b.bounds.error) << where;
  EXPECT_EQ(a.bounds.sphere.centre, b.bounds.sphere.centre) << where;
  EXPECT_EQ(a.bounds.sphere.radius, b.bounds.sphere.radius) << where;
}

}  // namespace tessera::testing
