#pragma once
// The exact-sort policy: what a mesh needs before a visibility sort of a given method, and
// whether the order that comes out can claim to be exact. MPVO is exact on a convex mesh; a
// non-convex one is convexified (mesh/copyleft, TetGen) so that MPVO over real + virtual cells
// is exact; where that is impossible the order is MPVO plus the pairwise fallback on the bare
// mesh, and says so.

#include <core/result.h>
#include <mesh/face_adjacency.h>
#include <mesh/tet_mesh.h>
#include <sort/visibility_sort.h>

#include <memory>
#include <string>

namespace tr {

// A mesh as it is sorted: maybe convexified (virtual tets appended), with its adjacency.
struct SortedMesh {
    std::shared_ptr<const TetMesh> mesh;  // the loaded mesh itself unless convexified
    FaceAdjacency adjacency;
    bool real_convex = false;    // the real tets alone form a convex solid
    bool convexified = false;    // virtual tets were added
    bool sorted_convex = false;  // what is sorted (real + virtual tets) is convex: checked
    std::string note;            // why a wanted convexification did not happen, and what is sorted
    std::string failure;         // just why (TetGen's reason, or that the build has no TetGen)
    double adjacency_ms = 0;
    double convexify_ms = 0;
};

// What the sorter runs, on which mesh, and what its orders may claim.
struct PreparedSort {
    std::shared_ptr<const SortedMesh> sorted;
    SortMethod requested = SortMethod::kAuto;
    SortMethod method = SortMethod::kMpvo;  // what VisibilitySorter::sort is asked to run
    // The method's orders are exact on the mesh actually sorted: an MPVO-family method and a
    // convex sorted mesh (checked on it, not inferred from the method's name). A view whose
    // sort broke a visibility cycle is still not exact (order_is_exact).
    bool exact = false;
    std::string note;  // why a requested exact order is not exact, if so ("" otherwise)

    const TetMesh& mesh() const { return *sorted->mesh; }
    const FaceAdjacency& adjacency() const { return sorted->adjacency; }
};

// Whether `requested` wants the convexified mesh: auto and exact do when the mesh is not convex.
bool wants_convexification(SortMethod requested);

// Builds the sorted mesh for `mesh` (shared, not copied, unless convexified): adjacency, the
// convexity test and, when `convexify` and the mesh is not convex, TetGen's fill (when built
// with TetGen; otherwise, or when TetGen fails, `note` says why and the bare mesh is used).
// Errors: those of build_face_adjacency (three tets on a face). Cost: O(tets) plus TetGen's.
Result<SortedMesh> prepare_sorted_mesh(std::shared_ptr<const TetMesh> mesh, bool convexify);

// The policy: auto -> MPVO on the convex (or convexified) mesh; exact -> the same, and a note
// when the mesh could not be made convex; mpvo, mpvonc, centroid as they are (mpvonc and
// centroid never claim exactness; mpvo only on a convex mesh). `sorted` must come from
// prepare_sorted_mesh(mesh, wants_convexification(requested)) or be convex.
PreparedSort prepare_sort(std::shared_ptr<const SortedMesh> sorted, SortMethod requested);

// Whether one view's order is exact: the prepared sort claims it and the sort broke no cycle.
bool order_is_exact(const PreparedSort& prepared, const SortStats& stats);

}  // namespace tr
