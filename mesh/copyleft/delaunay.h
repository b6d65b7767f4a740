#pragma once
// Delaunay tetrahedralization of a point cloud (CGAL, GPL-3: target tetrender::delaunay, built
// when TETRENDER_WITH_CGAL is on).

#include <core/result.h>
#include <mesh/tet_mesh.h>
#include <mesh/unstructured_mesh.h>

#include <cstddef>

namespace tr {

struct DelaunayReport {
    std::size_t num_input_points = 0;
    std::size_t num_duplicate_points = 0;  // points equal to an earlier one, merged into it
    std::size_t num_dropped_tets = 0;      // Delaunay cells too flat to evaluate in doubles (rare)
    std::size_t num_tets = 0;              // tets in the result
    double seconds = 0;                    // wall time of the whole call
};

// The Delaunay tetrahedralization of cloud.points (its cells, if any, are ignored): the convex
// hull of the points filled with tets whose circumspheres hold no other point. Predicates are
// exact (CGAL's Exact_predicates_inexact_constructions_kernel); ties between cospherical
// points are broken symbolically, so the result is deterministic.
//
// Points with identical coordinates are merged into the first of them. The result keeps the
// distinct points in their input order (point i of the result is the i-th distinct input
// point) and carries cloud.point_fields along (a merged point keeps the first point's values);
// cell fields are ignored. Tets have positive orientation (tet_mesh.h); source_cell(t) == t.
//
// Errors (kInvalidMesh): a non-finite coordinate (names the point), fewer than 4 distinct
// points, all points coplanar or collinear; a point field with the wrong size
// (kInvalidArgument). Failures inside CGAL come back as kInternal.
// Cost: O(n log n) expected for n points, single-threaded: 0.4 s for 100k random points
// (670k tets), 5 s and a peak of about 750 bytes per point for a million (6.7M tets).
Result<TetMesh> delaunay_tetrahedralize(const UnstructuredMesh& cloud,
                                        DelaunayReport* report = nullptr);

}  // namespace tr
