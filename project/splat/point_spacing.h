#pragma once
// The local spacing of scattered points (issue 14: splats of a point cloud without a radius
// array): each point's h, the edge of the cube of space it stands for, so that a kernel scaled
// to h gives every region of the cloud the optical depth of its own density, dense regions not
// too opaque and sparse ones without holes.

#include <core/math.h>

#include <span>
#include <vector>

namespace tr {

// The neighbour whose distance sets h: on a cubic lattice of spacing a the 32nd nearest other
// point lies at 2a (6 at a, 12 at a sqrt 2, 8 at a sqrt 3, 6 at 2a).
inline constexpr int kSpacingNeighbour = 32;

// h of each point: half the distance to its kSpacingNeighbour-th nearest other point. Exact
// inside a cubic lattice (a); for points scattered uniformly at random with density n, 0.982
// n^(-1/3) on average and n h^3 = 0.958 (measured in tests/splat/point_spacing_test.cpp), so a
// constant field's optical depth comes out within a few percent of the slab's (0.979 and 0.996
// measured in the two halves of a cloud whose densities differ 8-fold, where one global
// spacing gives 1.905 and 0.238); larger at a cloud's boundary
// (fewer neighbours on one side). With kSpacingNeighbour or fewer other points, every point gets
// half the largest distance between two of them. Points that coincide count as neighbours at
// distance 0. Cost: a k-d tree, O(n log n) to build, about O(k log n) a point, in parallel.
// Precondition: finite points.
std::vector<float> local_spacing(std::span<const Vec3> points);

}  // namespace tr
