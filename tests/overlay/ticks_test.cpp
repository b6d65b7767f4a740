// Tick values: nice numbers (1, 2, 5 x 10^k) covering the range.
#include <overlay/ticks.h>

#include <gtest/gtest.h>

#include <cmath>

namespace tr {
namespace {

// Whether v is 1, 2 or 5 times a power of ten.
bool is_nice(double v) {
    const double m = v / std::pow(10.0, std::floor(std::log10(v) + 1e-9));
    return std::abs(m - 1) < 1e-9 || std::abs(m - 2) < 1e-9 || std::abs(m - 5) < 1e-9;
}

TEST(Ticks, LinearTicksAreMultiplesOfANiceStepCoveringTheRange) {
    const std::vector<std::pair<double, double>> ranges = {
        {0, 1},          {-3.7, 12.2},     {1e-5, 3e-5}, {293.15, 913.15}, {-1, 1},
        {0.013, 0.0171}, {-250000, 1.5e6}, {7.0, 7.3},   {1, 10}};
    for (const auto& [lo, hi] : ranges) {
        SCOPED_TRACE(std::to_string(lo) + " .. " + std::to_string(hi));
        const Ticks t = linear_ticks(lo, hi, 6);
        ASSERT_GE(t.values.size(), 2u);
        EXPECT_LE(t.values.size(), 6u);
        EXPECT_TRUE(is_nice(t.step)) << t.step;
        for (std::size_t i = 0; i < t.values.size(); ++i) {
            const double v = t.values[i];
            EXPECT_GE(v, lo);
            EXPECT_LE(v, hi);
            const double k = v / t.step;
            EXPECT_NEAR(k, std::round(k), 1e-6) << v;  // a multiple of the step
            if (i > 0) {
                EXPECT_NEAR(v - t.values[i - 1], t.step, t.step * 1e-9);
            }
        }
        // Covering: no gap of a whole step at either end.
        EXPECT_LT(t.values.front() - lo, t.step);
        EXPECT_LT(hi - t.values.back(), t.step);
    }
}

TEST(Ticks, LogTicksArePowersOfTenWhenTheRangeSpansDecades) {
    const Ticks t = log_ticks(1e-3, 250.0, 6);
    ASSERT_EQ(t.values.size(), 6u);  // 1e-3 .. 1e2
    for (std::size_t i = 0; i < t.values.size(); ++i) {
        EXPECT_NEAR(std::log10(t.values[i]), -3.0 + i, 1e-12);
    }
    const Ticks many = log_ticks(1e-6, 1e6, 5);  // 13 decades: every 3rd
    EXPECT_LE(many.values.size(), 5u);
    EXPECT_GE(many.values.size(), 4u);
    const Ticks narrow = log_ticks(3.0, 40.0, 6);  // one power: 1, 2, 5 x 10^k
    ASSERT_GE(narrow.values.size(), 2u);
    for (double v : narrow.values) {
        EXPECT_TRUE(is_nice(v)) << v;
        EXPECT_GE(v, 3.0);
        EXPECT_LE(v, 40.0);
    }
    EXPECT_TRUE(log_ticks(-1.0, 10.0).values.empty());
}

TEST(Ticks, Labels) {
    EXPECT_EQ(tick_label(0.25, 0.05), "0.25");
    EXPECT_EQ(tick_label(1500, 500), "1500");
    EXPECT_EQ(tick_label(-0.0, 0.1), "0.0");
    EXPECT_EQ(tick_label(-2, 1), "-2");
    EXPECT_EQ(tick_label(1e6, 0), "1e+06");
    EXPECT_EQ(range_label(293.15), "293.1");
}

}  // namespace
}  // namespace tr
