// Sorting the meshes that need the copyleft parts: random Delaunay meshes (CGAL), on which MPVO
// is exact from every viewpoint (Edelsbrunner), and non-convex meshes made exact by
// convexification (TetGen).
#include <core/config.h>
#include <mesh/face_adjacency.h>
#include <mesh/tetrahedralize.h>
#include <sort/order_verifier.h>
#include <sort/visibility_sort.h>
#include <tests/support/mixed_grid.h>
#include <tests/support/sanitized.h>

#if TETRENDER_HAS_CGAL
#include <mesh/copyleft/delaunay.h>
#endif
#if TETRENDER_HAS_TETGEN
#include <mesh/copyleft/convexify.h>
#include <mesh/copyleft/cylinder_demo.h>
#endif

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

namespace tr {
namespace {

struct Tally {
    std::size_t pairs = 0, violations = 0, cycles = 0, fallback = 0;
};

Tally check_views(const TetMesh& mesh, SortMethod method, int views, std::uint64_t seed,
                  bool inside = false) {
    auto adjacency = build_face_adjacency(mesh);
    EXPECT_TRUE(adjacency.ok()) << adjacency.error().to_string();
    VisibilitySorter sorter;
    std::vector<CellId> order;
    Tally tally;
    for (int v = 0; v < views; ++v) {
        const CameraFrame frame(random_view(mesh.bounds(), seed * 100 + v, v % 3 == 2, inside), 64,
                                64);
        const SortStats stats =
            sorter.sort(mesh, *adjacency, SortView::from_camera(frame), method, order);
        EXPECT_EQ(order.size(), mesh.num_real_tets());
        const OrderCheck check = check_order(mesh, order, frame);
        tally.pairs += check.pairs;
        tally.violations += check.violations;
        tally.cycles += stats.cells_in_cycles;
        tally.fallback += stats.by_fallback;
    }
    return tally;
}

#if TETRENDER_HAS_CGAL
TEST(SortDelaunay, MpvoHasNoViolationsAndNoCycles) {
    // Four random clouds; one in the sanitizer build (tests/support/sanitized.h: 93 s for four).
    const std::uint32_t clouds = testing::kSanitized ? 1 : 4;
    for (std::uint32_t seed = 1; seed <= clouds; ++seed) {
        SCOPED_TRACE(seed);
        std::mt19937 rng(seed);
        std::uniform_real_distribution<double> u(0.0, 1.0);
        UnstructuredMesh cloud;
        for (int i = 0; i < 3000; ++i) cloud.points.emplace_back(u(rng), u(rng), 0.6 * u(rng));
        auto mesh = delaunay_tetrahedralize(cloud);
        ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
        const Tally mpvo = check_views(*mesh, SortMethod::kMpvo, 9, seed);
        const Tally inside = check_views(*mesh, SortMethod::kMpvo, 3, seed, true);
        const Tally centroid = check_views(*mesh, SortMethod::kCentroid, 9, seed);
        std::printf(
            "[ delaunay %zu tets ] pairs %zu: mpvo %zu violations, %zu in cycles; "
            "centroid %zu violations (%.1f%%)\n",
            mesh->num_tets(), mpvo.pairs, mpvo.violations, mpvo.cycles, centroid.violations,
            100.0 * centroid.violations / std::max<std::size_t>(1, centroid.pairs));
        EXPECT_GT(mpvo.pairs, 10000u);
        EXPECT_EQ(mpvo.violations, 0u);
        EXPECT_EQ(mpvo.fallback, 0u);
        EXPECT_EQ(inside.violations, 0u);
        EXPECT_GT(centroid.violations, 0u);
    }
}
#endif

#if TETRENDER_HAS_TETGEN
TetMesh convexified(TetMesh mesh) {
    auto adjacency = build_face_adjacency(mesh);
    EXPECT_TRUE(adjacency.ok());
    auto report = convexify(mesh, *adjacency);
    EXPECT_TRUE(report.ok()) << report.error().to_string();
    return mesh;
}

TEST(SortConvexified, NonConvexMeshesBecomeExact) {
    using testing::MixedGridOptions;
    struct Case {
        const char* name;
        bool (*skip)(int, int, int);
        int n, nz;
    };
    // (An extruded L and a notched box are not among them: their bare MPVO orders measured no
    // violation, the L in 2.6M pairs over 168 views, the notch (a 4x4x3 box less a 2x2x2 corner,
    // since the split is ordered by coordinates) in 168 views outside and 42 inside, so they
    // cannot show a change.)
    const Case cases[] = {
        {"Z", [](int i, int j, int) { return (i >= 2 && j < 2) || (i < 3 && j >= 3); }, 5, 2},
        {"ring", [](int i, int j, int) { return i >= 1 && i <= 3 && j >= 1 && j <= 3; }, 5, 2},
        {"U", [](int i, int j, int) { return i >= 2 && j >= 2 && i < 5 && j < 5; }, 6, 2},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.name);
        MixedGridOptions o;
        o.nx = o.ny = c.n;
        o.nz = c.nz;
        o.skip_box = c.skip;
        auto bare = tetrahedralize(testing::make_mixed_grid(o));
        ASSERT_TRUE(bare.ok());
        const Tally without = check_views(*bare, SortMethod::kMpvo, 12, 11);
        const TetMesh filled = convexified(*bare);
        EXPECT_GT(filled.num_virtual_tets(), 0u);
        const Tally with = check_views(filled, SortMethod::kMpvo, 12, 11);
        const Tally inside = check_views(filled, SortMethod::kMpvo, 4, 12, true);
        std::printf("[ %s ] pairs %zu: mpvo %zu violations bare, %zu convexified\n", c.name,
                    with.pairs, without.violations, with.violations);
        // Bare, MPVO is wrong along some rays (measured 543 Z, 1526 ring, 1317 U);
        // convexified, along none.
        EXPECT_GT(without.violations, 0u);
        EXPECT_GT(with.pairs, 1000u);
        EXPECT_EQ(with.violations, 0u);
        EXPECT_EQ(inside.violations, 0u);
    }
}

TEST(SortConvexified, TheDemoCylinderHole) {
    CylinderDemoOptions options;
    options.target_tets = 15000;
    auto demo = make_cylinder_demo(options);
    ASSERT_TRUE(demo.ok()) << demo.error().to_string();
    const Tally without = check_views(*demo, SortMethod::kMpvo, 6, 21);
    const Tally centroid = check_views(*demo, SortMethod::kCentroid, 6, 21);
    const TetMesh filled = convexified(*demo);
    const Tally with = check_views(filled, SortMethod::kMpvo, 6, 21);
    std::printf(
        "[ demo %zu tets ] pairs %zu: mpvo %zu violations bare, %zu convexified; "
        "centroid %zu\n",
        demo->num_tets(), with.pairs, without.violations, with.violations, centroid.violations);
    EXPECT_GT(without.violations, 0u);  // measured 168
    EXPECT_GT(with.pairs, 1000u);
    EXPECT_EQ(with.violations, 0u);
}
#endif

}  // namespace
}  // namespace tr
