// The samples of particle-based rendering: each segment's lattice stratifies its repetitions and
// finds the points below a probability without visiting the others; the inverse-CDF depth follows
// the exact distribution of the first particle (Kolmogorov-Smirnov against a quadrature of the
// extinction that shares no code with the closed form).
#include <project/pbvr/pbvr_sampling.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

namespace tr {
namespace {

TEST(SegmentLattice, EveryRepetitionTakesOneStratum) {
    for (int n : {1, 2, 7, 64, 100, 987, 1024}) {
        for (std::uint64_t key : {1u, 2u, 3u}) {
            SCOPED_TRACE(testing::Message() << n << " key " << key);
            const SegmentLattice lattice(n, key);
            EXPECT_EQ(std::gcd(lattice.generator(), n), 1);
            const double shift = 0.3712;  // not on a stratum boundary
            std::vector<int> strata(n, 0), seen(n, 0);
            lattice.for_each_below(1.0, shift, [&](int r, double u) {
                ASSERT_GE(r, 0);
                ASSERT_LT(r, n);
                EXPECT_NEAR(u, lattice.uniform(shift, r), 1e-12);
                ++seen[r];
                ++strata[std::min(n - 1, static_cast<int>(u * n))];
            });
            for (int j = 0; j < n; ++j) {
                EXPECT_EQ(strata[j], 1) << j;
                EXPECT_EQ(seen[j], 1) << j;
            }
        }
    }
    // Different keys give different generators (the lattices of segments on one ray differ).
    std::vector<int> generators;
    for (std::uint64_t key = 0; key < 20; ++key)
        generators.push_back(SegmentLattice(64, key).generator());
    std::sort(generators.begin(), generators.end());
    EXPECT_GT(std::unique(generators.begin(), generators.end()) - generators.begin(), 10);
}

TEST(SegmentLattice, VisitsExactlyTheRepetitionsBelow) {
    for (int trial = 0; trial < 300; ++trial) {
        const int n = 1 + trial % 97;
        const SegmentLattice lattice(n, hash_key(4, trial));
        const double shift = uniform01(hash_key(1, trial));
        const double p = uniform01(hash_key(3, trial)) * (trial % 10 == 0 ? 0.0 : 1.0);
        std::vector<int> expected;
        for (int r = 0; r < n; ++r) {
            if (lattice.uniform(shift, r) < p) expected.push_back(r);
        }
        std::vector<int> got;
        lattice.for_each_below(p, shift, [&](int r, double) { got.push_back(r); });
        std::sort(got.begin(), got.end());
        EXPECT_EQ(got, expected) << "n " << n << " p " << p << " shift " << shift;
    }
}

// Optical depth over [0, w] by the midpoint rule on kappa (no closed form shared).
double quadrature_depth(const TransferFunction& tf, double sf, double sb, double length, double w) {
    const int steps = 4000;
    double sum = 0;
    for (int i = 0; i < steps; ++i) {
        const double x = (i + 0.5) / steps * w;
        sum += tf.extinction(sf + (sb - sf) * x / length);
    }
    return sum * w / steps;
}

TEST(InverseCdfDepth, FollowsTheFirstParticleDistribution) {
    const TransferFunction tf =
        TransferFunction::create({{0, {1, 0, 0}}, {1, {0, 0, 1}}},
                                 {{0.0, 0.0}, {0.3, 0.05}, {0.6, 0.9}, {1.0, 0.2}}, 0.5)
            .value();
    struct Segment {
        double sf, sb, length;
    };
    // Rising through the peak, falling, constant, thin and optically thick.
    const ExtinctionIntegral phi(tf);
    for (const Segment seg :
         {Segment{0.1, 0.9, 1.0}, Segment{0.95, 0.2, 0.7}, Segment{0.6, 0.6, 0.4},
          Segment{0.55, 0.65, 3.0}, Segment{0.0, 0.25, 0.2}}) {
        SCOPED_TRACE(testing::Message() << seg.sf << " -> " << seg.sb << " over " << seg.length);
        const double depth = seg.length * tf.mean_extinction(seg.sf, seg.sb);
        const double total = quadrature_depth(tf, seg.sf, seg.sb, seg.length, seg.length);
        EXPECT_NEAR(depth, total, 1e-6 * std::max(1.0, total));
        const double alpha = -std::expm1(-depth);
        const int n = 20000;
        std::vector<double> w(n);
        for (int i = 0; i < n; ++i) {
            w[i] = inverse_cdf_depth(phi, seg.sf, seg.sb, seg.length, depth,
                                     uniform01(hash_key(7, i)));
            ASSERT_GE(w[i], 0.0);
            ASSERT_LE(w[i], seg.length);
        }
        std::sort(w.begin(), w.end());
        // Kolmogorov-Smirnov: largest gap between the empirical CDF and the exact one,
        // alpha(w) / alpha(length), evaluated at 200 order statistics.
        double d = 0;
        for (int i = 0; i < n; i += n / 200) {
            const double exact =
                -std::expm1(-quadrature_depth(tf, seg.sf, seg.sb, seg.length, w[i])) / alpha;
            d = std::max({d, std::abs(exact - static_cast<double>(i) / n),
                          std::abs(exact - static_cast<double>(i + 1) / n)});
        }
        // Critical value at 0.1% significance: 1.95 / sqrt(n) = 0.0138.
        EXPECT_LT(d, 1.95 / std::sqrt(n));
    }
}

TEST(ExtinctionIntegral, MatchesQuadratureAndInvertsItself) {
    // Pieces rising, falling, flat at zero, a step (two points at one scalar), clamped ends.
    const TransferFunction tf =
        TransferFunction::create(
            {{0, {1, 1, 1}}},
            {{0.0, 0.1}, {0.2, 0.0}, {0.4, 0.0}, {0.6, 0.8}, {0.6, 0.3}, {1.0, 0.95}}, 0.7)
            .value();
    const ExtinctionIntegral phi(tf);
    for (double s : {-0.5, 0.0, 0.1, 0.3, 0.5, 0.6, 0.61, 0.9, 1.0, 1.7}) {
        // The extinction's integral from 0 to s by the midpoint rule on each piece between the
        // opacity points (the step at 0.6 is a jump of kappa).
        std::vector<double> cuts = {0.0, s};
        for (double c : {0.2, 0.4, 0.6, 1.0}) {
            if (c > std::min(0.0, s) && c < std::max(0.0, s)) cuts.push_back(c);
        }
        std::sort(cuts.begin(), cuts.end());
        double sum = 0;
        for (std::size_t c = 0; c + 1 < cuts.size(); ++c) {
            const int steps = 20000;
            const double h = (cuts[c + 1] - cuts[c]) / steps;
            for (int i = 0; i < steps; ++i) sum += h * tf.extinction(cuts[c] + (i + 0.5) * h);
        }
        EXPECT_NEAR(phi.at(s) - phi.at(0.0), s >= 0 ? sum : -sum, 1e-8) << s;
    }
    for (double from : {-0.3, 0.05, 0.3, 0.55, 0.65, 1.2}) {
        for (double to : {-0.4, 0.1, 0.45, 0.6, 0.9, 1.5}) {
            if (from == to) continue;
            const double span = std::abs(phi.at(to) - phi.at(from));
            for (double f : {0.0, 0.1, 0.5, 0.9, 1.0}) {
                const double s = phi.advance(from, to, f * span);
                EXPECT_NEAR(std::abs(phi.at(s) - phi.at(from)), f * span, 1e-10)
                    << from << " -> " << to << " by " << f;
                EXPECT_GE(s, std::min(from, to) - 1e-12);
                EXPECT_LE(s, std::max(from, to) + 1e-12);
            }
        }
    }
}

TEST(InverseCdfDepth, InvertsTheOpacityExactly) {
    const TransferFunction tf =
        TransferFunction::create({{0, {1, 1, 1}}}, {{0.0, 0.0}, {1.0, 0.99}}, 0.1).value();
    for (double v : {0.0, 1e-6, 0.25, 0.5, 0.999999}) {
        const double depth = 2.0 * tf.mean_extinction(0.2, 1.0);
        const double w = inverse_cdf_depth(ExtinctionIntegral(tf), 0.2, 1.0, 2.0, depth, v);
        const double at = w * tf.mean_extinction(0.2, 0.2 + 0.4 * w);
        EXPECT_NEAR(-std::expm1(-at), v * -std::expm1(-depth), 1e-9) << v;
    }
    // A transparent piece before the opacity starts: the particle lies after it.
    const TransferFunction late =
        TransferFunction::create({{0, {1, 1, 1}}}, {{0.0, 0.0}, {0.5, 0.0}, {1.0, 0.5}}, 1.0)
            .value();
    const double depth = 1.0 * late.mean_extinction(0.0, 1.0);
    for (int i = 0; i < 100; ++i) {
        EXPECT_GE(inverse_cdf_depth(ExtinctionIntegral(late), 0.0, 1.0, 1.0, depth,
                                    uniform01(hash_key(9, i))),
                  0.5 - 1e-9);
    }
}

TEST(ParticleDepth, NamesAndFixedPlaces) {
    for (const char* name : {"inverse-cdf", "entry", "middle", "exit", "random"}) {
        ASSERT_TRUE(parse_particle_depth(name).has_value()) << name;
        EXPECT_EQ(particle_depth_name(*parse_particle_depth(name)), name);
    }
    EXPECT_FALSE(parse_particle_depth("center").has_value());
    const TransferFunction tf =
        TransferFunction::create({{0, {1, 1, 1}}}, {{0.0, 0.5}}, 1.0).value();
    const ExtinctionIntegral phi(tf);
    EXPECT_EQ(particle_depth(ParticleDepth::kEntry, phi, 0, 0, 2, 1, 0.3), 0.0);
    EXPECT_EQ(particle_depth(ParticleDepth::kMiddle, phi, 0, 0, 2, 1, 0.3), 1.0);
    EXPECT_EQ(particle_depth(ParticleDepth::kExit, phi, 0, 0, 2, 1, 0.3), 2.0);
    EXPECT_DOUBLE_EQ(particle_depth(ParticleDepth::kRandom, phi, 0, 0, 2, 1, 0.3), 0.6);
}

}  // namespace
}  // namespace tr
