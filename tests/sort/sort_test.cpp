// Visibility orders checked by the independent ray verifier over many random views.
#include <mesh/face_adjacency.h>
#include <mesh/tetrahedralize.h>
#include <sort/order_verifier.h>
#include <sort/visibility_sort.h>
#include <tests/mesh/mixed_grid.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

namespace tr {
namespace {

using testing::make_mixed_grid;
using testing::MixedGridOptions;

struct Tally {
    std::size_t pairs = 0, violations = 0, fallback = 0, cycles = 0;
};

Tally check_views(const TetMesh& mesh, SortMethod method, int views, std::uint32_t seed,
                  bool inside = false, int size = 48) {
    auto adjacency = build_face_adjacency(mesh);
    EXPECT_TRUE(adjacency.ok());
    VisibilitySorter sorter;
    std::vector<CellId> order;
    Tally tally;
    for (int v = 0; v < views; ++v) {
        const bool ortho = v % 3 == 2;
        const CameraFrame frame(random_view(mesh.bounds(), seed * 1000 + v, ortho, inside), size,
                                size);
        const SortStats stats =
            sorter.sort(mesh, *adjacency, SortView::from_camera(frame), method, order);
        EXPECT_EQ(stats.cells, mesh.num_real_tets());
        // A permutation of the real cells.
        std::vector<std::uint8_t> seen(mesh.num_tets(), 0);
        for (CellId c : order) {
            EXPECT_FALSE(mesh.is_virtual(c));
            EXPECT_EQ(seen[c]++, 0);
        }
        const OrderCheck check = check_order(mesh, order, frame);
        EXPECT_EQ(check.missing_cells, 0u);
        tally.pairs += check.pairs;
        tally.violations += check.violations;
        tally.fallback += stats.by_fallback;
        tally.cycles += stats.cells_in_cycles;
    }
    return tally;
}

TEST(Sort, MpvoIsExactOnConvexMixedMeshes) {
    for (std::uint32_t seed = 1; seed <= 6; ++seed) {
        SCOPED_TRACE(seed);
        MixedGridOptions o;
        o.seed = seed;
        o.nx = o.ny = o.nz = 4;
        auto mesh = tetrahedralize(make_mixed_grid(o));
        ASSERT_TRUE(mesh.ok());
        const Tally mpvo = check_views(*mesh, SortMethod::kMpvo, 12, seed);
        EXPECT_GT(mpvo.pairs, 1000u);
        EXPECT_EQ(mpvo.violations, 0u);
        EXPECT_EQ(mpvo.cycles, 0u);
        const Tally centroid = check_views(*mesh, SortMethod::kCentroid, 12, seed);
        std::printf(
            "[ mixed %u ] pairs %zu: mpvo %zu violations (fallback %zu cells), centroid "
            "%zu violations\n",
            seed, mpvo.pairs, mpvo.violations, mpvo.fallback, centroid.violations);
    }
}

TEST(Sort, MpvoIsExactWithTheEyeInside) {
    MixedGridOptions o;
    o.nx = o.ny = o.nz = 5;
    auto mesh = tetrahedralize(make_mixed_grid(o));
    ASSERT_TRUE(mesh.ok());
    const Tally t = check_views(*mesh, SortMethod::kMpvo, 9, 99, /*inside=*/true);
    EXPECT_GT(t.pairs, 1000u);
    EXPECT_EQ(t.violations, 0u);
}

TEST(Sort, DegenerateViewsAlongGridPlanes) {
    // Eye on face planes and view directions parallel to faces: the axis-aligned grid seen
    // straight along an axis, from a point on a grid plane.
    MixedGridOptions o;
    o.nx = o.ny = o.nz = 3;
    o.p_pyramids = o.p_tets = o.p_wedge_column = 0.3;
    auto mesh = tetrahedralize(make_mixed_grid(o));
    ASSERT_TRUE(mesh.ok());
    auto adjacency = build_face_adjacency(*mesh);
    ASSERT_TRUE(adjacency.ok());
    VisibilitySorter sorter;
    std::vector<CellId> order;
    struct View {
        Vec3 eye, focal, up;
    };
    // Eyes on grid planes (x = 1 and y = 1, ...) looking along the axes and along a face
    // diagonal, so that whole families of faces are edge-on.
    const View views[] = {{{1, 1, -5}, {1, 1, 1.5}, {0, 1, 0}},
                          {{1.5, 2, 9}, {1.5, 2, 1.5}, {0, 1, 0}},
                          {{-4, 1, 1}, {1.5, 1, 1}, {0, 0, 1}},
                          {{-3, -3, 1}, {1.5, 1.5, 1}, {0, 0, 1}}};
    for (bool ortho : {false, true}) {
        for (const View& view : views) {
            for (int size : {40, 41}) {  // pixel rays off and on the grid planes
                Camera c;
                c.position = view.eye;
                c.focal_point = view.focal;
                c.view_up = view.up;
                c.parallel = ortho;
                c.parallel_scale = 3;
                c.view_angle = 60;
                const CameraFrame frame(c, size, size);
                sorter.sort(*mesh, *adjacency, SortView::from_camera(frame), SortMethod::kMpvo,
                            order);
                const OrderCheck check = check_order(*mesh, order, frame);
                EXPECT_GT(check.pairs, 0u);
                EXPECT_EQ(check.violations, 0u)
                    << "eye " << view.eye.x << " " << view.eye.y << " " << view.eye.z;
            }
        }
    }
}

TEST(Sort, NonConvexWithoutFillIsReportedNotHidden) {
    MixedGridOptions o;
    o.nx = o.ny = 6;
    o.nz = 2;
    o.skip_box = [](int i, int j, int) { return i >= 2 && j >= 2 && i < 5 && j < 5; };  // a U
    auto mesh = tetrahedralize(make_mixed_grid(o));
    ASSERT_TRUE(mesh.ok());
    const Tally mpvo = check_views(*mesh, SortMethod::kMpvo, 12, 5);
    const Tally mpvonc = check_views(*mesh, SortMethod::kMpvoNonConvex, 12, 5);
    const Tally centroid = check_views(*mesh, SortMethod::kCentroid, 12, 5);
    std::printf("[ U shape, no fill ] pairs %zu: mpvo %zu, mpvonc %zu, centroid %zu violations\n",
                mpvo.pairs, mpvo.violations, mpvonc.violations, centroid.violations);
    EXPECT_GT(mpvo.pairs, 0u);
    EXPECT_LE(mpvonc.violations, mpvo.violations);
}

// Three long thin tets that overlap cyclically (each one above the next), like three sticks:
// no order is right for every ray; the pairwise sort must say so.
TEST(Sort, PairwiseSortReportsAVisibilityCycle) {
    std::vector<Vec3> points;
    std::vector<Tet> tets;
    for (int s = 0; s < 3; ++s) {
        const double a = 2 * M_PI * s / 3;
        const Vec3 along(std::cos(a), std::sin(a), 0);
        const Vec3 across(-along.y, along.x, 0);
        // Rises from z = 0 at one end to z = 1 at the other; the next stick crosses its high end.
        const Vec3 start = -1.2 * along + 0.5 * across;
        const Vec3 end = 1.2 * along + 0.5 * across;
        const auto base = static_cast<PointId>(points.size());
        points.push_back(start + Vec3(0, 0, 0.0));
        points.push_back(end + Vec3(0, 0, 1.0));
        points.push_back(start + 0.15 * across + Vec3(0, 0, 0.05));
        points.push_back(start + Vec3(0, 0, 0.15));
        tets.push_back({base, PointId(base + 1), PointId(base + 2), PointId(base + 3)});
    }
    auto mesh = TetMesh::create(points, tets);
    ASSERT_TRUE(mesh.ok());
    ASSERT_EQ(mesh->num_tets(), 3u);
    Camera c;
    c.position = Vec3(0, 0, 10);
    c.focal_point = Vec3(0, 0, 0);
    c.view_up = Vec3(0, 1, 0);
    c.parallel = true;
    c.parallel_scale = 2;
    const CameraFrame frame(c, 256, 256);
    std::vector<CellId> order;
    SortStats stats;
    pairwise_exact_order(*mesh, {0, 1, 2}, SortView::from_camera(frame), order, stats);
    EXPECT_EQ(order.size(), 3u);
    EXPECT_GE(stats.cells_in_cycles, 1u);
    EXPECT_GE(stats.cycles_broken, 1u);
    // No order of a cycle is right everywhere, and the verifier sees it.
    EXPECT_GT(check_order(*mesh, order, frame).violations, 0u);
}

TEST(Sort, PairwiseSortAgreesWithMpvoOnAConvexMesh) {
    MixedGridOptions o;
    o.nx = o.ny = o.nz = 2;
    auto mesh = tetrahedralize(make_mixed_grid(o));
    ASSERT_TRUE(mesh.ok());
    for (int v = 0; v < 6; ++v) {
        const CameraFrame frame(random_view(mesh->bounds(), 300 + v, v % 2 == 1, false), 48, 48);
        std::vector<CellId> cells(mesh->num_tets());
        for (CellId t = 0; t < cells.size(); ++t) cells[t] = t;
        std::vector<CellId> order;
        SortStats stats;
        pairwise_exact_order(*mesh, cells, SortView::from_camera(frame), order, stats);
        EXPECT_EQ(stats.cells_in_cycles, 0u);
        EXPECT_EQ(check_order(*mesh, order, frame).violations, 0u);
    }
}

TEST(Sort, MethodNamesRoundTrip) {
    for (auto name : {"auto", "mpvo", "mpvonc", "exact", "centroid"}) {
        auto m = parse_sort_method(name);
        ASSERT_TRUE(m.has_value());
        EXPECT_EQ(sort_method_name(*m), name);
    }
    EXPECT_FALSE(parse_sort_method("bogus").has_value());
}

}  // namespace
}  // namespace tr
