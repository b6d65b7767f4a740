#pragma once
// Progress reporting for long steps: a callback the library calls and the apps draw.

#include <functional>
#include <string_view>

namespace tr {

// Called with a stage name ("reading", "tetrahedralizing", ...) and the fraction done in
// [0, 1]. May be empty. Called from the calling thread only, at most a few hundred times per
// stage.
using ProgressFn = std::function<void(std::string_view stage, double fraction)>;

inline void report_progress(const ProgressFn& progress, std::string_view stage, double fraction) {
    if (progress) progress(stage, fraction);
}

}  // namespace tr
