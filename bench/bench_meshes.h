#pragma once
// Generated inputs for the benchmarks: structured grids of hexahedra, split into tets once and
// cached per size.

#include <mesh/tet_mesh.h>
#include <mesh/unstructured_mesh.h>

namespace tr::bench {

// An n^3 grid of unit hexahedra, slightly perturbed (not axis-aligned faces everywhere).
// With `hole`, the middle third of the columns in x and y is left out: a block with a square
// hole through it (non-convex).
UnstructuredMesh hex_grid(int n, bool hole = false);

// hex_grid(n, hole) split into tets, with a float point scalar "scalar". Built once per
// (n, hole).
const TetMesh& tet_grid(int n, bool hole = false);

// The n for about `tets` tets: round(cbrt(tets / 6)).
int grid_size_for(double tets);

}  // namespace tr::bench
