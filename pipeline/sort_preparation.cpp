#include <core/config.h>
#include <core/stopwatch.h>
#include <pipeline/loaded_mesh.h>
#include <pipeline/sort_preparation.h>

#if TETRENDER_HAS_TETGEN
#include <mesh/copyleft/convexify.h>
#endif

#include <chrono>

namespace tr {

bool wants_convexification(SortMethod requested) {
    return requested == SortMethod::kAuto || requested == SortMethod::kExact;
}

Result<SortedMesh> prepare_sorted_mesh(std::shared_ptr<const TetMesh> mesh, bool convexify) {
    SortedMesh sorted;
    auto start = std::chrono::steady_clock::now();
    TR_TRY(sorted.adjacency, build_face_adjacency(*mesh));
    sorted.adjacency_ms = ms_since(start);
    sorted.real_convex = check_convexity(*mesh, sorted.adjacency).convex;
    sorted.mesh = std::move(mesh);
    if (convexify && !sorted.real_convex) {
#if TETRENDER_HAS_TETGEN
        start = std::chrono::steady_clock::now();
        auto filled = std::make_shared<TetMesh>(*sorted.mesh);
        auto report = tr::convexify(*filled, sorted.adjacency);
        if (report.ok()) {
            auto adjacency = build_face_adjacency(*filled);
            if (adjacency.ok()) {
                sorted.adjacency = std::move(adjacency).value();
                sorted.mesh = std::move(filled);
                sorted.convexified = true;
            } else {
                sorted.failure =
                    "convexification gave an invalid mesh: " + adjacency.error().message;
            }
        } else {
            sorted.failure = "convexification failed: " + report.error().message;
        }
        sorted.convexify_ms = ms_since(start);
#else
        sorted.failure = "no TetGen in this build to convexify the non-convex mesh";
#endif
        if (!sorted.failure.empty())
            sorted.note = sorted.failure + ": sorting the bare mesh, not exact";
    }
    sorted.sorted_convex =
        sorted.convexified
            ? check_convexity(*sorted.mesh, sorted.adjacency, ConvexityOf::kAllTets).convex
            : sorted.real_convex;
    if (sorted.convexified && !sorted.sorted_convex && sorted.note.empty()) {
        sorted.failure = "the convexified mesh is not convex";
        sorted.note = sorted.failure + ": not exact";
    }
    return sorted;
}

PreparedSort prepare_sort(std::shared_ptr<const SortedMesh> sorted, SortMethod requested) {
    PreparedSort prepared;
    prepared.requested = requested;
    prepared.method = wants_convexification(requested) ? SortMethod::kMpvo : requested;
    prepared.exact = claims_exactness(prepared.method, sorted->sorted_convex);
    if (wants_convexification(requested)) prepared.note = sorted->note;
    prepared.sorted = std::move(sorted);
    return prepared;
}

bool order_is_exact(const PreparedSort& prepared, const SortStats& stats) {
    return prepared.exact && stats.cells_in_cycles == 0;
}

}  // namespace tr
