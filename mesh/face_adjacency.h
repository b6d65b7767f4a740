#pragma once
// Face adjacency of a TetMesh: for every tet face the tet on the other side or kNoCell; the
// boundary faces; the convexity test.

#include <core/result.h>
#include <mesh/surface_mesh.h>
#include <mesh/tet_mesh.h>

#include <array>
#include <cstddef>
#include <vector>

namespace tr {

struct BoundaryFace {
    CellId tet;
    int face;  // 0..3, opposite vertex `face` (tet_mesh.h)
};

struct FaceAdjacency {
    // neighbors[t][k]: the tet sharing face k of tet t, or kNoCell on the boundary.
    std::vector<std::array<CellId, 4>> neighbors;
    // Every face with no neighbour, in tet order.
    std::vector<BoundaryFace> boundary_faces;

    std::size_t byte_size() const;
};

// Builds the adjacency of all tets (real and virtual). Faces match by their three point ids,
// so coincident points must be merged first. Errors (kInvalidMesh, naming a tet) when three or
// more tets share a face. Cost: O(tets) time (bucketing by smallest vertex), 16 bytes per tet
// plus a temporary of about 40 bytes per tet; single-threaded.
Result<FaceAdjacency> build_face_adjacency(const TetMesh& mesh);

// The three point ids of face k of tet t, outward (counter-clockwise seen from outside t).
std::array<PointId, 3> face_points(const TetMesh& mesh, CellId t, int k);

// The boundary of the real tets as a triangle surface (faces whose other side is nothing or a
// virtual tet), outward, on a copy of the mesh's points. Cost: O(tets).
SurfaceMesh boundary_surface(const TetMesh& mesh, const FaceAdjacency& adjacency);

struct ConvexityReport {
    bool convex = false;
    std::size_t num_boundary_components = 0;  // connected pieces of the boundary surface
    std::size_t num_reflex_edges = 0;         // boundary edges where the surface folds inwards
    std::size_t num_nonmanifold_edges = 0;    // boundary edges with other than two faces
};

// Which cells make the solid whose convexity is checked.
enum class ConvexityOf {
    kRealTets,  // the mesh's own cells: virtual tets count as outside
    kAllTets,   // real and virtual together (a convexified mesh: what MPVO sorts)
};

// Is the boundary of the chosen tets the boundary of their convex hull? True when the boundary
// is one closed surface with no reflex edge (an edge is reflex when a neighbouring face's far
// vertex lies outside the plane of the other by more than rel_tolerance times the bounds'
// diagonal). `adjacency` must be of `mesh` without virtual tets or with them. Cost:
// O(boundary faces).
ConvexityReport check_convexity(const TetMesh& mesh, const FaceAdjacency& adjacency,
                                ConvexityOf of = ConvexityOf::kRealTets,
                                double rel_tolerance = 1e-9);

}  // namespace tr
