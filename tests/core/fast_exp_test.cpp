// core/fast_exp.h against the double-precision exponential over its whole range.
#include <core/fast_exp.h>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace tr {
namespace {

TEST(FastExp, WithinAFloatOfExpOverItsRange) {
    double worst_relative = 0, worst_one_minus = 0;
    for (int i = 0; i <= 2000000; ++i) {
        // Uniform over [-87, 0], and densely near 0 where 1 - e^x is what compositing uses.
        for (float x :
             {-87.0f * static_cast<float>(i) / 2e6f, -1e-3f * static_cast<float>(i) / 2e6f}) {
            const double exact = std::exp(static_cast<double>(x));
            const double got = exp_nonpositive(x);
            worst_relative = std::max(worst_relative, std::abs(got - exact) / exact);
            worst_one_minus = std::max(worst_one_minus, std::abs((1 - got) - (1 - exact)));
        }
    }
    std::printf("relative error %.2e, of 1 - e^x %.2e\n", worst_relative, worst_one_minus);
    // Measured 8.3e-8 and 4.8e-8.
    EXPECT_LT(worst_relative, 1.2e-7);
    EXPECT_LT(worst_one_minus, 6e-8);
    EXPECT_EQ(exp_nonpositive(0.0f), 1.0f);  // so a zero optical depth leaves a pixel as it is
    EXPECT_NEAR(exp_nonpositive(-1000.0f), std::exp(-87.0), 1e-40);
    EXPECT_NEAR(exp_nonpositive(std::numeric_limits<float>::quiet_NaN()), std::exp(-87.0), 1e-40);
}

TEST(FastExp, BoundedWithinAFloatOfExpBothSides) {
    double worst = 0;
    for (int i = -1000000; i <= 1000000; ++i) {
        const float x = 87.0f * static_cast<float>(i) / 1e6f;
        const double exact = std::exp(static_cast<double>(x));
        worst = std::max(worst, std::abs(exp_bounded(x) - exact) / exact);
    }
    std::printf("relative error over [-87, 87] %.2e\n", worst);
    // Measured 8.2e-8 (as exp_nonpositive's below 0).
    EXPECT_LT(worst, 1.2e-7);
    EXPECT_FLOAT_EQ(exp_bounded(1000.0f), std::exp(87.0f));
    EXPECT_EQ(exp_bounded(0.0f), 1.0f);
}

}  // namespace
}  // namespace tr
