// Procedural meshes for the oracle and property tests: closed genus 0 and
// genus > 0, open meshes with boundaries, every valence from 3 to 12 and
// poles of 20+, plus random edge flips and random feature tags from fixed
// seeds, so that the suites cover far more than hand-picked cases.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/loop/level_builder.h"
#include "core/util/vec3.h"

namespace tessera::testing {

struct TestMesh {
  std::string name;
  BaseTopology topology;
  std::vector<Vec3> points;
};

TestMesh icosahedron();
TestMesh bipyramid(int n);          // poles of valence n, genus 0
TestMesh torus(int nu, int nv);     // regular valence 6, genus 1
TestMesh openGrid(int nu, int nv);  // a bumpy patch with a boundary
TestMesh diskWithPole(int n);       // open fan: interior pole of valence n
TestMesh doubleTorus();             // genus 2, irregular valences

// Flips `count` random flippable edges (fixed seed): valences spread out.
TestMesh withRandomFlips(const TestMesh& mesh, int count, uint32_t seed);
// Random creases (sharpness drawn from {0.5, 1, 2, 2.5, inf, random}) on
// about `edgeFraction` of the edges, and random vertex sharpness (corners,
// cusps) on about `vertexFraction` of the vertices.
TestMesh withRandomTags(const TestMesh& mesh, double edgeFraction, double vertexFraction, uint32_t seed);
// Small random displacement of every point (fixed seed), to leave symmetry.
TestMesh withJitter(const TestMesh& mesh, double amount, uint32_t seed);

}  // namespace tessera::testing
