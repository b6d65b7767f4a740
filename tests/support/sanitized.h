#pragma once
// Whether this test runs in the sanitizer build (scripts/test.sh --sanitize: ASan + UBSan on
// the library, ASan on the tests' own code), where the library runs 3 to 10 times slower.
// Tests whose point is numerical accuracy over many or large inputs run in full in the Release
// build and on a part of their inputs here: the sanitizers check memory and undefined behaviour
// along the code paths, which the part takes, not the numbers, which the Release build checks.

#include <vector>

#ifndef TETRENDER_SANITIZED
#define TETRENDER_SANITIZED 0
#endif

namespace tr::testing {

inline constexpr bool kSanitized = TETRENDER_SANITIZED != 0;

// All of `cases`, or in the sanitizer build those `keep_when_sanitized` accepts.
template <class Cases, class Keep>
std::vector<typename Cases::value_type> sanitized_subset(const Cases& cases,
                                                         Keep keep_when_sanitized) {
    std::vector<typename Cases::value_type> kept;
    for (const auto& c : cases) {
        if (!kSanitized || keep_when_sanitized(c)) kept.push_back(c);
    }
    return kept;
}

}  // namespace tr::testing
