// The segment shader on its own: the closed-form mean extinction, the default integrator against
// the exact one on random segments from optically thin to opaque through transfer functions
// with kinks, steps, zero plateaus and many control points, and the tables the viewer samples.
#include <project/reference_raycaster.h>
#include <project/segment_shader.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

namespace tr {
namespace {

TransferFunction make_tf(std::vector<ColorPoint> c, std::vector<OpacityPoint> o, double unit) {
    return TransferFunction::create(std::move(c), std::move(o), unit).value();
}

// Viridis at 11 points over [lo, hi].
std::vector<ColorPoint> viridis(double lo, double hi) {
    const double rgb[11][3] = {{0.267, 0.005, 0.329}, {0.283, 0.141, 0.458}, {0.254, 0.265, 0.53},
                               {0.207, 0.372, 0.553}, {0.164, 0.471, 0.558}, {0.128, 0.567, 0.551},
                               {0.135, 0.659, 0.518}, {0.267, 0.749, 0.441}, {0.478, 0.821, 0.318},
                               {0.741, 0.873, 0.15},  {0.993, 0.906, 0.144}};
    std::vector<ColorPoint> points;
    for (int i = 0; i < 11; ++i) {
        points.push_back({lo + (hi - lo) * i / 10.0, Vec3(rgb[i][0], rgb[i][1], rgb[i][2])});
    }
    return points;
}

struct NamedTf {
    std::string name;
    TransferFunction tf;
    double max_levels;  // the default integrator's largest difference from exact, in levels
};

// The transfer functions of the tests, each with the default integrator's bound against exact
// in 8-bit levels (the measured largest difference per segment plus a margin of about 0.1; all
// within the half level the default promises).
std::vector<NamedTf> corpus() {
    std::vector<NamedTf> tfs;
    const double lo = -3.87, hi = 0.72;  // the ventilation grid's scalar range
    // tetrender's quick scene: opacity from 0 to 0.3 over the range.
    tfs.push_back(
        {"quick", make_tf(viridis(lo, hi), {{lo, 0.0}, {hi, 0.3}}, 0.34), 0.4});  // measured 0.28
    // Optically thick: opacity 0.5 at 0.3 of the range, 0.85 at the top, unit 0.25.
    tfs.push_back(
        {"thick",
         make_tf(viridis(lo, hi), {{lo, 0.0}, {lo + 0.3 * (hi - lo), 0.5}, {hi, 0.85}}, 0.25),
         0.4});  // measured 0.28
    // Nearly opaque everywhere.
    tfs.push_back(
        {"opaque", make_tf(viridis(lo, hi), {{lo, 0.97}, {hi, 0.97}}, 0.1), 0.4});  // measured 0.25
    // Jet-like colours with sharp turns; opacity falling to a zero plateau, a steep ramp, a
    // step down at 0.8 and near 1 at the top.
    tfs.push_back(
        {"steps",
         make_tf(
             {{0, {0, 0, 0.5}},
              {0.1, {0, 0, 1}},
              {0.35, {0, 1, 1}},
              {0.5, {1, 1, 0}},
              {0.65, {1, 0, 0}},
              {1, {0.5, 0, 0}}},
             {{0, 0.2}, {0.3, 0.0}, {0.5, 0.0}, {0.55, 0.9}, {0.8, 0.95}, {0.8, 0.3}, {1, 0.99}},
             0.5),
         0.45});  // measured 0.35
    // 200 colour and 120 opacity control points (more than the old fixed cap of 61 cuts; too
    // many to align the table's nodes with): the table's axes are uniform.
    std::vector<ColorPoint> many_c;
    for (int i = 0; i < 200; ++i) {
        const double s = i / 199.0;
        many_c.push_back({s, Vec3(0.5 + 0.5 * std::sin(9 * s), 0.5 + 0.5 * std::cos(7 * s),
                                  0.5 + 0.5 * std::sin(3 + 13 * s))});
    }
    std::vector<OpacityPoint> many_o;
    for (int i = 0; i < 120; ++i) {
        const double s = i / 119.0;
        many_o.push_back({s, 0.45 + 0.4 * std::sin(11 * s)});
    }
    tfs.push_back({"many points", make_tf(many_c, many_o, 0.2), 0.45});  // measured 0.32
    return tfs;
}

// The mean of the extinction over [s0, s1] by composite Simpson, split at the control points.
double numeric_mean_extinction(const TransferFunction& tf, double s0, double s1) {
    if (s0 > s1) std::swap(s0, s1);
    std::vector<double> cuts = {s0, s1};
    for (const OpacityPoint& p : tf.opacity_points()) {
        if (p.s > s0 && p.s < s1) cuts.push_back(p.s);
    }
    std::sort(cuts.begin(), cuts.end());
    double sum = 0.0;
    for (std::size_t c = 0; c + 1 < cuts.size(); ++c) {
        const double a = cuts[c], b = cuts[c + 1];
        if (!(b > a)) continue;
        constexpr int n = 2000;  // even
        const double h = (b - a) / n;
        // One-sided at the ends (a step sits on a cut): nudge inside.
        auto f = [&](int i) {
            const double s = std::clamp(a + i * h, a + 1e-12 * (b - a), b - 1e-12 * (b - a));
            return tf.extinction(s);
        };
        double piece = f(0) + f(n);
        for (int i = 1; i < n; ++i) piece += (i % 2 ? 4.0 : 2.0) * f(i);
        sum += piece * h / 3.0;
    }
    return sum / (s1 - s0);
}

TEST(SegmentShader, MeanExtinctionIsTheIntegralOfTheExtinction) {
    std::mt19937 rng(3);
    for (const NamedTf& c : corpus()) {
        SCOPED_TRACE(c.name);
        const double lo = c.tf.s_min(), hi = c.tf.s_max(), span = hi - lo;
        std::uniform_real_distribution<double> u(lo - 0.1 * span, hi + 0.1 * span);
        double worst = 0.0;
        for (int i = 0; i < 200; ++i) {
            const double s0 = u(rng), s1 = u(rng);
            const double closed = c.tf.mean_extinction(s0, s1);
            EXPECT_EQ(closed, c.tf.mean_extinction(s1, s0));
            const double numeric = numeric_mean_extinction(c.tf, s0, s1);
            worst = std::max(worst, std::abs(closed - numeric) / numeric);
        }
        std::printf("[ %s ] mean extinction: largest relative difference from Simpson %.2g\n",
                    c.name.c_str(), worst);
        EXPECT_LT(worst, 1e-9);  // measured 5.3e-11 (Simpson's own error by the steps)
        // A segment of no extent: the extinction there, also where the opacity vanishes.
        for (double s : {lo, lo + 0.37 * span, hi}) {
            EXPECT_NEAR(c.tf.mean_extinction(s, s), c.tf.extinction(s), 1e-12);
            EXPECT_NEAR(c.tf.mean_extinction(s, s + 1e-12 * span), c.tf.extinction(s),
                        1e-9 * (1 + c.tf.extinction(s)));
        }
    }
}

// Segments through a transfer function's range (and beyond it), spread from no scalar change to
// the whole range and from optically thin (r near 0) to opaque (r near 1; lengths up to 1e7
// unit distances): the default integrator against the exact one.
TEST(SegmentShader, DefaultIsWithinHalfALevelOfExact) {
    for (const NamedTf& c : corpus()) {
        SCOPED_TRACE(c.name);
        const SegmentShader pre(c.tf, Integrator::kPreintegrated, 1.0);
        const SegmentShader exact(c.tf, Integrator::kExact, 1.0);
        const double lo = c.tf.s_min(), hi = c.tf.s_max(), span = hi - lo;
        std::mt19937_64 rng(11);
        std::uniform_real_distribution<double> u(0.0, 1.0);
        double worst = 0.0;
        int thick = 0;
        const double spreads[] = {0.0, 0.002, 0.02, 0.2, 2.0};
        for (int i = 0; i < 20000; ++i) {
            double sf = lo + span * (-0.05 + 1.1 * u(rng));
            if (i % 7 == 0) sf = lo + span * 1e-3 * u(rng);  // by the lowest control point
            const double sb = sf + span * spreads[i % 5] * (u(rng) - 0.5);
            const double k = c.tf.mean_extinction(sf, sb);
            if (!(k > 0)) continue;
            const double r = i % 101 == 0 ? 1.0 - 1e-7 * u(rng) : u(rng);
            const double length = r / (1.0 - r) / k;
            thick += r > 0.9;
            const ShadedSegment a = pre.shade(sf, sb, length);
            const ShadedSegment b = exact.shade(sf, sb, length);
            const Vec3f d = glm::abs(a.color - b.color);
            worst = std::max({worst, static_cast<double>(d.x), static_cast<double>(d.y),
                              static_cast<double>(d.z), std::abs(double{a.alpha} - b.alpha)});
        }
        EXPECT_GT(thick, 1500);
        std::printf(
            "[ %s ] default vs exact: largest difference %.3f levels, %zu of %zu table "
            "cells integrated directly\n",
            c.name.c_str(), worst * 255, pre.direct_cells(), pre.table_cells());
        EXPECT_LE(worst * 255, c.max_levels);
    }
}

// The exact integrator splits at every control point the segment crosses, however many (it
// used to drop those beyond 61): against the reference's adaptive quadrature.
TEST(SegmentShader, ExactTakesEveryControlPoint) {
    std::vector<ColorPoint> colors;
    for (int i = 0; i <= 300; ++i) {
        colors.push_back({i / 300.0, i % 2 ? Vec3(1.0, 0.1, 0.0) : Vec3(0.0, 0.2, 1.0)});
    }
    const TransferFunction tf = make_tf(colors, {{0, 0.2}, {1, 0.6}}, 1.0);
    const SegmentShader exact(tf, Integrator::kExact, 1.0);
    double worst = 0.0;
    for (double sb : {0.3, 0.6, 1.0}) {
        for (double length : {0.05, 0.5, 3.0}) {
            const ShadedSegment s = exact.shade(0.0, sb, length);
            const SegmentIntegral ref = integrate_segment(tf, 0.0, sb, length, 1e-10);
            const Vec3f d = glm::abs(s.color - Vec3f(ref.color));
            worst = std::max({worst, static_cast<double>(d.x), static_cast<double>(d.y),
                              static_cast<double>(d.z)});
            EXPECT_NEAR(s.alpha, 1.0 - ref.transparency, 1e-6);
        }
    }
    std::printf("exact vs reference over 300 colour control points: largest difference %.2g\n",
                worst);
    EXPECT_LT(worst, 1e-6);  // measured 1.2e-7
}

// tables() keeps the layout the OpenGL renderer samples: (front, back, length) nodes holding
// what shade() gives there.
TEST(SegmentShader, PreintegratedTableKeepsItsLayout) {
    const TransferFunction tf = corpus()[1].tf;
    const double max_length = 0.8;
    const SegmentShader shader(tf, Integrator::kPreintegrated, max_length);
    const SegmentShaderTables t = shader.tables();
    ASSERT_EQ(t.pre_scalars, 64);
    ASSERT_EQ(t.pre_lengths, 32);
    ASSERT_EQ(t.preint_table.size(), std::size_t{64} * 64 * 32 * 4);
    EXPECT_EQ(t.s_lo, tf.s_min());
    EXPECT_EQ(t.s_hi, tf.s_max());
    EXPECT_EQ(t.max_length, max_length);
    for (int f : {0, 17, 63}) {
        for (int b : {0, 40, 63}) {
            for (int l : {0, 1, 31}) {
                const double sf = t.s_lo + (t.s_hi - t.s_lo) * f / 63.0;
                const double sb = t.s_lo + (t.s_hi - t.s_lo) * b / 63.0;
                const ShadedSegment s = shader.shade(sf, sb, max_length * l / 31.0);
                const float* texel = &t.preint_table[((f * 64 + b) * 32 + l) * 4];
                EXPECT_FLOAT_EQ(texel[0], s.color.x);
                EXPECT_FLOAT_EQ(texel[1], s.color.y);
                EXPECT_FLOAT_EQ(texel[2], s.color.z);
                EXPECT_FLOAT_EQ(texel[3], s.alpha);
                if (l == 0) {
                    EXPECT_EQ(texel[3], 0.0f);
                }
            }
        }
    }
    // The other integrators have no such table.
    EXPECT_TRUE(SegmentShader(tf, Integrator::kExact, 1.0).tables().preint_table.empty());
}

// The batch entry point is the single one, segment by segment, for every integrator.
TEST(SegmentShader, BatchShadesAsOneByOne) {
    const TransferFunction tf = corpus()[3].tf;
    std::vector<SegmentQuery> queries;
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(-0.1, 1.1);
    for (int i = 0; i < 500; ++i) queries.push_back({u(rng), u(rng), 0.01 + std::abs(u(rng))});
    for (Integrator integrator :
         {Integrator::kExact, Integrator::kPreintegrated, Integrator::kExpTexture}) {
        SCOPED_TRACE(std::string(integrator_name(integrator)));
        const SegmentShader shader(tf, integrator, 1.0);
        std::vector<ShadedSegment> out(queries.size());
        shader.shade(queries, out);
        for (std::size_t i = 0; i < queries.size(); ++i) {
            const ShadedSegment one =
                shader.shade(queries[i].s_front, queries[i].s_back, queries[i].length);
            ASSERT_EQ(out[i].color, one.color) << i;
            ASSERT_EQ(out[i].alpha, one.alpha) << i;
        }
    }
}

// What lets the renderer leave cells out: a transfer function clear over a scalar interval
// (zero opacity there, steps and plateaus included) and segments inside it shading to exactly
// nothing with every integrator.
TEST(SegmentShader, SegmentsWhereTheTransferFunctionIsClearShadeToNothing) {
    // Clear below 0.3 and on [0.6, 0.7] (a plateau between two ramps), a step up at 0.9.
    const TransferFunction tf =
        TransferFunction::create({{0.0, {0.2, 0.4, 0.9}}, {1.0, {0.9, 0.3, 0.1}}},
                                 {{0.1, 0.0},
                                  {0.3, 0.0},
                                  {0.45, 0.5},
                                  {0.6, 0.0},
                                  {0.7, 0.0},
                                  {0.8, 0.3},
                                  {0.9, 0.3},
                                  {0.9, 0.0},
                                  {1.0, 0.0}},
                                 0.5)
            .value();
    EXPECT_TRUE(tf.clear_between(-5.0, 0.3));
    EXPECT_TRUE(tf.clear_between(0.7, 0.6));  // either order
    EXPECT_TRUE(tf.clear_between(0.62, 0.68));
    EXPECT_TRUE(tf.clear_between(0.95, 7.0));  // beyond the last point: clamped to 0
    EXPECT_FALSE(tf.clear_between(0.25, 0.31));
    EXPECT_FALSE(tf.clear_between(0.55, 0.62));
    EXPECT_FALSE(tf.clear_between(0.2, 0.65));   // clear at both ends, not between
    EXPECT_FALSE(tf.clear_between(0.85, 0.95));  // across the step down
    EXPECT_FALSE(tf.clear_between(std::nan(""), 0.2));
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (Integrator integrator :
         {Integrator::kExact, Integrator::kPreintegrated, Integrator::kExpTexture}) {
        const SegmentShader shader(tf, integrator, 4.0);
        for (int i = 0; i < 2000; ++i) {
            // Inside one of the clear intervals, lengths up to the table's and beyond.
            const double lo = i % 2 ? 0.6 : -0.5, hi = i % 2 ? 0.7 : 0.3;
            const double s0 = lo + (hi - lo) * unit(rng), s1 = lo + (hi - lo) * unit(rng);
            ASSERT_TRUE(shader.clear_between(s0, s1));
            const ShadedSegment seg = shader.shade(s0, s1, 6.0 * unit(rng));
            EXPECT_EQ(seg.alpha, 0.0f);
            EXPECT_EQ(seg.color, Vec3f(0.0f));
        }
        // Not a shader that shades nothing anywhere.
        EXPECT_GT(shader.shade(0.4, 0.5, 1.0).alpha, 0.1f);
    }
}

}  // namespace
}  // namespace tr
