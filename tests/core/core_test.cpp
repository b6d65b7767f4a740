// Result<T>, errors and the parallel facade.
#include <core/parallel.h>
#include <core/result.h>

#include <gtest/gtest.h>

#include <atomic>
#include <numeric>
#include <vector>

namespace tr {
namespace {

Result<int> half(int x) {
    if (x % 2) return make_error(ErrorCode::kInvalidArgument, "odd number", "arg");
    return x / 2;
}

Result<int> quarter(int x) {
    TR_TRY(int h, half(x));
    return half(h);
}

TEST(Result, CarriesValuesAndErrors) {
    EXPECT_EQ(*quarter(8), 2);
    auto r = quarter(6);
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().to_string(), "arg: error: odd number");
    EXPECT_EQ(make_error(ErrorCode::kIo, "a\nb").to_string(), "error: a b");
}

TEST(Parallel, CoversEveryIndexOnceWhateverTheThreadCount) {
    for (int threads : {1, 2, 4}) {
        set_thread_count(threads);
        EXPECT_EQ(thread_count(), threads);
        std::vector<std::atomic<int>> hits(10007);
        parallel_for(0, hits.size(), 100, [&](std::size_t i) { hits[i]++; });
        for (auto& h : hits) ASSERT_EQ(h.load(), 1);
    }
    set_thread_count(0);
    EXPECT_GE(thread_count(), 1);
}

}  // namespace
}  // namespace tr
