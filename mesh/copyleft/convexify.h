#pragma once
// Convexification: fills the space between a non-convex TetMesh and a surrounding box with
// virtual tets, so that MPVO over real + virtual cells is exact (TetGen, AGPL-3: target
// tetrender::tetgen). MPVO is exact only on convex meshes (Williams 1992; Comba, Mitchell and
// Silva: "convexification").

#include <core/result.h>
#include <mesh/face_adjacency.h>
#include <mesh/tet_mesh.h>

#include <cstddef>

namespace tr {

struct ConvexifyOptions {
    // The box's sides lie this fraction of the bounds' largest side outside the bounds (> 0).
    double box_margin = 0.05;
};

struct ConvexifyReport {
    std::size_t num_virtual_tets = 0;
    std::size_t num_components = 0;  // connected components of the real tets (face-connected)
    double seconds = 0;
    bool already_convex = false;  // nothing to do: check_convexity said convex
};

// Appends virtual tets (TetMesh::append_virtual) filling an axis-aligned box around `mesh`
// minus the real tets. TetGen meshes the PLC made of every boundary face of the mesh, the six
// faces of the box and one hole point per connected component of the mesh (a tet centroid),
// with switches -pYQ: -Y puts no Steiner point on the input faces, so each boundary face of
// the mesh is exactly one face of one virtual tet and the union is a conforming mesh whose
// boundary is the box's 12 triangles. New points: the box's 8 corners and Steiner points TetGen
// adds inside the gap; the mesh's points are reused. Point fields get zeros at new points,
// cell fields zeros on virtual tets.
//
// `adjacency` must be build_face_adjacency(mesh); the mesh must have no virtual tets yet. A
// convex mesh (check_convexity) is left alone: report.already_convex, 0 virtual tets.
// Errors (the mesh is unchanged): virtual tets already present, adjacency of another mesh,
// box_margin <= 0 (kInvalidArgument); TetGen failing, typically because it cannot recover
// the boundary without Steiner points (-Y) or the boundary intersects itself (kInvalidMesh or
// kInternal, with TetGen's reason); the result failing the final check (the virtual tets'
// unshared faces must be exactly the mesh's boundary faces plus 12 box triangles, kInternal).
// The caller then falls back to a sort that does not need convexity.
// Cost: TetGen's on the boundary (0.02 s for 2,000 boundary faces, 0.3 s for 28,000), plus
// O(tets) for the components and O(virtual tets log) for the check.
Result<ConvexifyReport> convexify(TetMesh& mesh, const FaceAdjacency& adjacency,
                                  const ConvexifyOptions& options = {});

}  // namespace tr
