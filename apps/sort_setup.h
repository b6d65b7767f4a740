#pragma once
// Getting a mesh ready to sort with a given method: adjacency, the convexity test, and the
// convexification that makes MPVO exact on a non-convex mesh (when built with TetGen).

#include <core/result.h>
#include <mesh/face_adjacency.h>
#include <mesh/tet_mesh.h>
#include <sort/visibility_sort.h>

#include <string>

namespace tr::apps {

struct SortSetup {
    TetMesh mesh;  // the mesh, with virtual tets appended when convexified
    FaceAdjacency adjacency;
    bool convex = false;                    // the real mesh is convex
    bool convexified = false;               // virtual tets were added
    SortMethod method = SortMethod::kMpvo;  // what the sorter is asked to run
    bool exact = false;                     // whether that method's order claims exactness here
    std::string note;                       // why a requested exact method is not exact, if so
    double adjacency_ms = 0;
    double convexify_ms = 0;
};

// Resolves `requested` for `mesh` (moved in): auto -> mpvo on a convex mesh, otherwise the
// convexified mesh (exact); exact -> convexify if not convex; mpvo, mpvonc, centroid as they
// are. Without TetGen, or when convexification fails, exact/auto fall back to MPVO plus the
// pairwise fallback on the bare mesh, which is not exact: `note` says so.
Result<SortSetup> prepare_sort(TetMesh mesh, SortMethod requested);

}  // namespace tr::apps
