#pragma once
// Checking visibility orders against brute-force rays (`tetrender sort-check`): each sort
// method over random views of a mesh, each order counted by the independent verifier
// (sort/order_verifier.h).

#include <core/result.h>
#include <pipeline/pipeline.h>
#include <sort/order_verifier.h>

#include <cstdint>
#include <functional>
#include <vector>

namespace tr {

struct SortCheckOptions {
    std::vector<SortMethod> methods = {SortMethod::kMpvo, SortMethod::kMpvoNonConvex,
                                       SortMethod::kExact, SortMethod::kCentroid};
    int views = 8;
    int width = 128, height = 128;  // rays per view
    bool orthographic = false;
    bool inside = false;  // the eye inside the bounds (core/camera.h random_view)
    std::uint64_t seed = 1;
};

// One method and one view.
struct SortCheckRow {
    SortMethod method;
    int view = 0;
    bool claims_exact = false;  // the prepared sort claims exactness on this mesh
    bool convexified = false;
    OrderCheck check;
    SortStats stats;
};

struct SortCheckMethod {
    SortMethod method;
    PreparedSort prepared;
    std::size_t violations = 0;  // over all views
};

struct SortCheckReport {
    std::vector<SortCheckMethod> methods;
    std::vector<SortCheckRow> rows;
    // A method that claims exactness put cells the wrong way round in some view.
    bool exact_violated = false;
};

// Runs every method over the views; `on_method` (before its views: its preparation, e.g. to
// print a note) and `on_row` (after each view) may be empty. Errors: loading and preparing
// the mesh. Cost: per view, the sort plus the verifier's O(rays x cells per ray).
Result<SortCheckReport> check_sorts(Pipeline& pipeline, const SceneVolume& volume,
                                    const SortCheckOptions& options,
                                    const std::function<void(const SortCheckMethod&)>& on_method,
                                    const std::function<void(const SortCheckRow&)>& on_row);

}  // namespace tr
