#pragma once
// Volume meshing of a closed triangulated surface with TetGen (AGPL-3: target tetrender::tetgen,
// built when TETRENDER_WITH_TETGEN is on).

#include <core/result.h>
#include <mesh/surface_mesh.h>
#include <mesh/tet_mesh.h>

#include <string>

namespace tr {

struct TetgenOptions {
    // Radius-edge ratio bound of quality meshing (TetGen -q); 0: no quality meshing (TetGen
    // still refines with its default bound 2.0 when max_volume > 0).
    double quality_ratio = 2.0;
    // Largest tet volume (TetGen -a), in the surface's units cubed; 0: no bound. With a bound,
    // TetGen's final mesh optimization is off (-O0: its flips and smoothing can enlarge tets
    // past the bound) unless extra_switches has an 'O'.
    double max_volume = 0.0;
    // More TetGen switches, appended verbatim, e.g. "Y" (keep the surface triangles unsplit)
    // or "T0.00001". Only TetGen's switch letters, digits, '.', '/' and ',' are accepted;
    // switches that need inputs this function does not take (r, i, m, w), write files or
    // print help (g, k, h), or suppress the output read back (N, E, F, I) are rejected.
    std::string extra_switches;
    // A bound on the work: with max_volume > 0 the mesh has at least (enclosed volume) /
    // max_volume tets; more than this is refused before TetGen starts (5e7 tets: about 5 GB
    // and many minutes in TetGen).
    double max_tets = 5e7;
};

// Fills the volume enclosed by `surface` with tets: TetGen with -p (the triangles form a
// piecewise linear complex) and -Q (quiet), plus -q and -a from `options`. Nested closed
// surfaces bound cavities when surface.holes holds a point inside each cavity; the outside of
// the outermost surface is always removed. The result keeps the surface points first (in
// order, those used by tets), then TetGen's Steiner points; tets have positive orientation.
//
// Errors: no triangles, an index out of range, a repeated index, a non-finite point
// (kInvalidMesh, naming it); an open surface, i.e. an edge used by only one triangle
// (kInvalidMesh, naming the edge); a self-intersecting surface or facets too close for TetGen
// (kInvalidMesh, with TetGen's reason); bad switches (kInvalidArgument); a max_volume that asks
// for more than max_tets tets (kInvalidArgument, saying how many); other TetGen failures
// (kInternal). TetGen may print a line to stdout even with -Q.
// Cost: TetGen's, about 1 s per 300k tets, single-threaded.
Result<TetMesh> tetgen_mesh_surface(const SurfaceMesh& surface, const TetgenOptions& options = {});

}  // namespace tr
