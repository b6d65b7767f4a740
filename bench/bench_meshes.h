#pragma once
// Generated inputs for the benchmarks: structured grids of hexahedra, split into tets once and
// cached per size.

#include <mesh/tet_mesh.h>
#include <mesh/unstructured_mesh.h>

namespace tr::bench {

// An n^3 grid of unit hexahedra, slightly perturbed (not axis-aligned faces everywhere).
UnstructuredMesh hex_grid(int n);

// hex_grid(n) split into 6 n^3 tets, with a float point scalar "scalar". Built once per n.
const TetMesh& tet_grid(int n);

// The n for about `tets` tets: round(cbrt(tets / 6)).
int grid_size_for(double tets);

}  // namespace tr::bench
