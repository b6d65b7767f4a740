// The local spacing of scattered points (project/splat/point_spacing.h): the k-d tree search
// against a brute-force one, a lattice's spacing exactly, a random cloud's density, and what it is
// for: splats of a cloud of two densities give both halves the optical depth of a constant field,
// where one global spacing makes the dense half eight times as deep.
#include <project/splat/point_spacing.h>
#include <project/splat/splat_renderer.h>
#include <tests/support/test_scenes.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

namespace tr {
namespace {

using testing::camera_at;

std::vector<float> brute_force_spacing(const std::vector<Vec3>& points) {
    std::vector<float> h(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
        std::vector<double> d2;
        for (std::size_t j = 0; j < points.size(); ++j) {
            if (j != i) d2.push_back(glm::dot(points[j] - points[i], points[j] - points[i]));
        }
        std::nth_element(d2.begin(), d2.begin() + kSpacingNeighbour - 1, d2.end());
        h[i] = static_cast<float>(0.5 * std::sqrt(d2[kSpacingNeighbour - 1]));
    }
    return h;
}

std::vector<Vec3> random_points(std::size_t n, const Vec3& lo, const Vec3& hi, unsigned seed) {
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<Vec3> p(n);
    for (Vec3& q : p) q = lo + (hi - lo) * Vec3(u(random), u(random), u(random));
    return p;
}

TEST(LocalSpacing, TheTreeSearchFindsTheBruteForceNeighbour) {
    // A 3D cloud with duplicates, a flat one and a thin line-like one.
    std::vector<Vec3> cloud = random_points(600, Vec3(0), Vec3(1, 2, 0.5), 1);
    for (int i = 0; i < 40; ++i) cloud.push_back(cloud[static_cast<std::size_t>(i)]);
    std::vector<Vec3> flat = random_points(500, Vec3(0), Vec3(3, 1, 0), 2);
    std::vector<Vec3> thin = random_points(400, Vec3(0), Vec3(10, 0.01, 0.01), 3);
    for (const auto* points : {&cloud, &flat, &thin}) {
        const std::vector<float> got = local_spacing(*points);
        const std::vector<float> want = brute_force_spacing(*points);
        ASSERT_EQ(got.size(), want.size());
        for (std::size_t i = 0; i < got.size(); ++i) ASSERT_EQ(got[i], want[i]) << i;
    }
    // Too few points for the neighbour: half the widest distance.
    const std::vector<Vec3> few = {Vec3(0), Vec3(1, 0, 0), Vec3(0, 2, 0)};
    for (float h : local_spacing(few)) EXPECT_FLOAT_EQ(h, 0.5f * std::sqrt(5.0f));
    EXPECT_TRUE(local_spacing(std::vector<Vec3>{}).empty());
}

TEST(LocalSpacing, ALatticesInteriorIsItsSpacingAndACloudItsDensity) {
    std::vector<Vec3> lattice;
    for (int z = 0; z < 12; ++z)
        for (int y = 0; y < 12; ++y)
            for (int x = 0; x < 12; ++x) lattice.push_back(0.5 * Vec3(x, y, z));
    const std::vector<float> h = local_spacing(lattice);
    for (std::size_t i = 0; i < lattice.size(); ++i) {
        const Vec3& p = lattice[i];
        const bool interior = glm::all(glm::greaterThanEqual(p, Vec3(1.0))) &&
                              glm::all(glm::lessThanEqual(p, Vec3(4.5)));
        if (interior) {
            ASSERT_EQ(h[i], 0.5f) << i;
        } else {
            ASSERT_GE(h[i], 0.5f) << i;  // fewer neighbours on a side: larger
        }
    }
    // Uniformly random: h against n^(-1/3) over the points well inside.
    const std::size_t n = 40000;
    const std::vector<Vec3> cloud = random_points(n, Vec3(0), Vec3(1), 4);
    const std::vector<float> hc = local_spacing(cloud);
    double sum = 0, cube_sum = 0;
    int inside = 0;
    const double unit = std::cbrt(1.0 / static_cast<double>(n));
    for (std::size_t i = 0; i < n; ++i) {
        if (glm::any(glm::lessThan(cloud[i], Vec3(0.15))) ||
            glm::any(glm::greaterThan(cloud[i], Vec3(0.85))))
            continue;
        sum += hc[i] / unit;
        cube_sum += std::pow(hc[i] / unit, 3.0);
        ++inside;
    }
    std::printf("random cloud: mean h %.4f n^(-1/3), mean h^3 n %.4f over %d points\n",
                sum / inside, cube_sum / inside, inside);
    // Measured 0.9824 and 0.9577 (the 32nd neighbour's distance is Gamma-distributed); the
    // optical depth of a constant field goes as n h^3.
    EXPECT_NEAR(sum / inside, 0.982, 0.01);
    EXPECT_NEAR(cube_sum / inside, 0.958, 0.015);
}

TEST(LocalSpacing, SplatsOfACloudOfTwoDensitiesAreEquallyDeep) {
    // x < 2: 8 times as dense as x > 2; a constant field seen along -z through 4 units.
    std::vector<Vec3> points = random_points(64000, Vec3(0, 0, 0), Vec3(2, 4, 4), 5);
    const std::vector<Vec3> sparse = random_points(8000, Vec3(2, 0, 0), Vec3(4, 4, 4), 6);
    points.insert(points.end(), sparse.begin(), sparse.end());
    const std::vector<float> scalar(points.size(), 1.0f);
    const TransferFunction tf = TransferFunction::create({{1, Vec3(1)}}, {{1, 0.05}}, 1.0).value();
    const double slab = tf.extinction(1.0) * 4.0;
    const CameraFrame frame(camera_at({2, 2, 30}, {2, 2, 2}, true, 4.0), 128, 128);
    const SplatFootprint footprint(SplatKernel::kCrawfisMax);
    const std::vector<float> local = local_spacing(points);
    for (const bool use_local : {true, false}) {
        SplatInputs in;
        in.points = points;
        in.scalar = scalar;
        in.spacing = lattice_spacing(points);
        if (use_local) in.radius = local;
        in.tf = &tf;
        in.footprint = &footprint;
        in.camera = &frame;
        const Image image = render_splats(in);
        // Mean optical depth over the slab's, in each half, away from the sides.
        double depth[2] = {0, 0};
        int count[2] = {0, 0};
        for (int y = 0; y < 128; ++y) {
            for (int x = 0; x < 128; ++x) {
                const Vec3 o = frame.pixel_ray(x, y).origin;
                if (o.y < 0.6 || o.y > 3.4 || std::abs(o.x - 2.0) < 0.6 || o.x < 0.6 || o.x > 3.4)
                    continue;
                const int half = o.x < 2.0 ? 0 : 1;
                depth[half] += -std::log1p(-static_cast<double>(image.at(x, y).r)) / slab;
                ++count[half];
            }
        }
        const double dense = depth[0] / count[0], thin = depth[1] / count[1];
        std::printf(
            "%s spacing: optical depth over the slab's: dense half %.3f, sparse half %.3f\n",
            use_local ? "local" : "global", dense, thin);
        if (use_local) {
            // Measured 0.979 and 0.996: both as deep as the slab, within 2 to 4%.
            EXPECT_NEAR(dense, 0.979, 0.02);
            EXPECT_NEAR(thin, 0.996, 0.02);
            EXPECT_LT(std::abs(dense - thin), 0.04);
        } else {
            // One spacing for both: the dense half 8 times the sparse one (measured 1.905 and
            // 0.238).
            EXPECT_GT(dense / thin, 7.0);
        }
    }
}

}  // namespace
}  // namespace tr
