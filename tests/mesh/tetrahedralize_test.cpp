// Property tests of the conforming split, the adjacency and the convexity test on random mixed
// meshes.
#include <core/parallel.h>
#include <mesh/face_adjacency.h>
#include <mesh/tetrahedralize.h>
#include <tests/support/mixed_grid.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <tuple>

namespace tr {
namespace {

using testing::box_boundary_triangles;
using testing::make_mixed_grid;
using testing::MixedGridOptions;
using testing::random_rotation_scale;

TEST(Tetrahedralize, RandomMixedMeshesAreConformingAndConserveVolume) {
    for (std::uint32_t seed = 1; seed <= 25; ++seed) {
        SCOPED_TRACE(seed);
        std::mt19937 rng(seed);
        MixedGridOptions o;
        o.seed = seed;
        o.nx = 2 + static_cast<int>(rng() % 5);
        o.ny = 2 + static_cast<int>(rng() % 5);
        o.nz = 2 + static_cast<int>(rng() % 5);
        o.linear = random_rotation_scale(rng);
        o.offset = Vec3(3.0, -2.0, 7.5);
        double expected = 0;
        const UnstructuredMesh input = make_mixed_grid(o, &expected);

        TetrahedralizeReport report;
        auto mesh = tetrahedralize(input, {}, &report);
        ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
        EXPECT_EQ(report.num_inverted_cells, 0u);
        EXPECT_EQ(report.num_degenerate_cells, 0u);
        EXPECT_EQ(report.num_degenerate_tets, 0u);
        EXPECT_EQ(report.num_merged_points, 0u);

        double volume = 0;
        for (CellId t = 0; t < mesh->num_tets(); ++t) {
            const double v = mesh->tet_volume(t);
            ASSERT_GT(v, 0.0) << "tet " << t;
            volume += v;
        }
        EXPECT_NEAR(volume, expected, 1e-12 * expected);

        auto adjacency = build_face_adjacency(*mesh);
        ASSERT_TRUE(adjacency.ok()) << adjacency.error().to_string();
        // No cracks: the only unshared faces are the outer box's, two per boundary quad.
        EXPECT_EQ(adjacency->boundary_faces.size(), box_boundary_triangles(o));
        // Neighbours are symmetric and share exactly the face's three points.
        for (CellId t = 0; t < mesh->num_tets(); ++t) {
            for (int k = 0; k < 4; ++k) {
                const CellId n = adjacency->neighbors[t][k];
                if (n == kNoCell) continue;
                int back = -1;
                for (int m = 0; m < 4; ++m) {
                    if (adjacency->neighbors[n][m] == t) back = m;
                }
                ASSERT_GE(back, 0);
                auto f = face_points(*mesh, t, k);
                auto g = face_points(*mesh, n, back);
                std::sort(f.begin(), f.end());
                std::sort(g.begin(), g.end());
                EXPECT_EQ(f, g);
            }
        }
        const ConvexityReport convexity = check_convexity(*mesh, *adjacency);
        EXPECT_TRUE(convexity.convex);
        EXPECT_EQ(convexity.num_boundary_components, 1u);
    }
}

// The split and the adjacency run in parallel chunks (16384 cells each) joined in order: the
// tets, their sources, the report and the neighbours are the same whatever the thread count.
TEST(Tetrahedralize, SameTetsAndNeighboursWhateverTheThreadCount) {
    MixedGridOptions o;
    o.nx = o.ny = 26;
    o.nz = 16;  // 10816 boxes of 1 to 12 cells: 40,000-odd cells, three chunks
    o.seed = 11;
    const UnstructuredMesh input = make_mixed_grid(o);
    ASSERT_GT(input.num_cells(), 16384u * 2);
    auto run = [&](int threads) {
        set_thread_count(threads);
        TetrahedralizeReport report;
        TetMesh mesh = tetrahedralize(input, {}, &report).value();
        FaceAdjacency adjacency = build_face_adjacency(mesh).value();
        set_thread_count(0);
        return std::make_tuple(std::move(mesh), std::move(adjacency), report);
    };
    const auto [one, one_adjacency, one_report] = run(1);
    const auto [two, two_adjacency, two_report] = run(2);
    const auto [five, five_adjacency, five_report] = run(5);
    for (const auto* other : {&two, &five}) {
        ASSERT_EQ(one.num_tets(), other->num_tets());
        EXPECT_TRUE(std::equal(one.tets().begin(), one.tets().end(), other->tets().begin()));
        EXPECT_EQ(one.source_cells(), other->source_cells());
        EXPECT_EQ(one.points(), other->points());
    }
    for (const auto* other : {&two_adjacency, &five_adjacency}) {
        EXPECT_EQ(one_adjacency.neighbors, other->neighbors);
        EXPECT_EQ(one_adjacency.boundary_faces.size(), other->boundary_faces.size());
    }
    for (const auto* other : {&two_report, &five_report}) {
        EXPECT_EQ(one_report.input_cells, other->input_cells);
        EXPECT_EQ(one_report.num_degenerate_tets, other->num_degenerate_tets);
        EXPECT_EQ(one_report.num_inverted_cells, other->num_inverted_cells);
        EXPECT_EQ(one_report.num_tets, other->num_tets);
    }
    // Not a trivial mesh: every kind of cell, interior faces matched.
    EXPECT_GE(one_report.input_cells.size(), 3u);
    EXPECT_GT(one_adjacency.boundary_faces.size(), 0u);
    EXPECT_LT(one_adjacency.boundary_faces.size(), one.num_tets());
}

TEST(Tetrahedralize, MirroredMeshReportsInvertedCellsAndKeepsVolume) {
    MixedGridOptions o;
    o.linear = glm::dmat3(1.0);
    o.linear[0][0] = -1.0;  // mirror x: every cell inverted by VTK's convention
    double expected = 0;
    const UnstructuredMesh input = make_mixed_grid(o, &expected);
    TetrahedralizeReport report;
    auto mesh = tetrahedralize(input, {}, &report);
    ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
    EXPECT_EQ(report.num_inverted_cells, input.num_cells());
    EXPECT_NEAR(mesh->real_volume(), -expected, 1e-12 * std::abs(expected));
    for (CellId t = 0; t < mesh->num_tets(); ++t) EXPECT_GT(mesh->tet_volume(t), 0.0);
}

TEST(Tetrahedralize, DuplicatedPointsAreMergedSoCellsBecomeNeighbours) {
    MixedGridOptions o;
    o.duplicate_points = true;  // tet boxes too: their diagonals follow the coordinates
    const UnstructuredMesh input = make_mixed_grid(o);
    TetrahedralizeReport report;
    auto merged = tetrahedralize(input, {}, &report);
    ASSERT_TRUE(merged.ok());
    EXPECT_GT(report.num_merged_points, 0u);
    EXPECT_EQ(input.num_points() - report.num_merged_points, merged->num_points());
    auto adjacency = build_face_adjacency(*merged);
    ASSERT_TRUE(adjacency.ok());
    EXPECT_EQ(adjacency->boundary_faces.size(), box_boundary_triangles(o));

    TetrahedralizeOptions no_merge;
    no_merge.merge_points = false;
    auto unmerged = tetrahedralize(input, no_merge);
    ASSERT_TRUE(unmerged.ok());
    auto loose = build_face_adjacency(*unmerged);
    ASSERT_TRUE(loose.ok());
    // Only faces inside each input cell are shared: many more boundary faces.
    EXPECT_GT(loose->boundary_faces.size(), 3 * box_boundary_triangles(o));
}

TEST(Tetrahedralize, TolerantMergeJoinsNearlyCoincidentPoints) {
    MixedGridOptions o;
    o.duplicate_points = true;
    o.p_tets = 0;  // tet boxes' diagonals follow the unjittered points, the split's the jittered
    UnstructuredMesh input = make_mixed_grid(o);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> jitter(-1e-9, 1e-9);
    for (Vec3& p : input.points) p += Vec3(jitter(rng), jitter(rng), jitter(rng));
    auto exact = tetrahedralize(input);
    ASSERT_TRUE(exact.ok());
    TetrahedralizeOptions tolerant;
    tolerant.merge_tolerance = 1e-6;
    auto merged = tetrahedralize(input, tolerant);
    ASSERT_TRUE(merged.ok());
    auto adjacency = build_face_adjacency(*merged);
    ASSERT_TRUE(adjacency.ok());
    EXPECT_EQ(adjacency->boundary_faces.size(), box_boundary_triangles(o));
    EXPECT_LT(merged->num_points(), exact->num_points());
}

TEST(Tetrahedralize, LShapeIsNotConvex) {
    MixedGridOptions o;
    o.nx = o.ny = o.nz = 4;
    o.skip_box = [](int i, int j, int) { return i >= 2 && j >= 2; };
    double expected = 0;
    auto mesh = tetrahedralize(make_mixed_grid(o, &expected));
    ASSERT_TRUE(mesh.ok());
    EXPECT_NEAR(mesh->real_volume(), expected, 1e-12 * expected);
    auto adjacency = build_face_adjacency(*mesh);
    ASSERT_TRUE(adjacency.ok());
    const ConvexityReport c = check_convexity(*mesh, *adjacency);
    EXPECT_FALSE(c.convex);
    EXPECT_GT(c.num_reflex_edges, 0u);
    EXPECT_EQ(c.num_boundary_components, 1u);
}

TEST(Tetrahedralize, TwoSeparateBlocksAreNotConvex) {
    MixedGridOptions o;
    o.nx = 5;
    o.ny = o.nz = 2;
    o.skip_box = [](int i, int, int) { return i == 2; };
    auto mesh = tetrahedralize(make_mixed_grid(o));
    ASSERT_TRUE(mesh.ok());
    auto adjacency = build_face_adjacency(*mesh);
    ASSERT_TRUE(adjacency.ok());
    const ConvexityReport c = check_convexity(*mesh, *adjacency);
    EXPECT_FALSE(c.convex);
    EXPECT_EQ(c.num_boundary_components, 2u);
}

UnstructuredMesh single_cell(CellType type, std::vector<Vec3> points) {
    UnstructuredMesh m;
    m.points = std::move(points);
    std::vector<std::int64_t> ids(m.points.size());
    for (std::size_t i = 0; i < ids.size(); ++i) ids[i] = static_cast<std::int64_t>(i);
    m.add_cell(type, ids);
    return m;
}

TEST(Tetrahedralize, EveryCellTypeHasItsVolume) {
    const std::vector<Vec3> cube = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                    {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
    struct Case {
        CellType type;
        std::vector<Vec3> points;
        double volume;
        std::size_t tets;
    };
    std::vector<Vec3> voxel = {cube[0], cube[1], cube[3], cube[2],
                               cube[4], cube[5], cube[7], cube[6]};
    std::vector<Vec3> quadratic_tet = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    for (int i = 0; i < 6; ++i) quadratic_tet.push_back({0.3, 0.3, 0.3});  // mid nodes unused
    std::vector<Vec3> pentagon_prism;
    for (int layer = 0; layer < 2; ++layer) {
        for (int i = 0; i < 5; ++i) {
            const double a = 2 * M_PI * i / 5;
            pentagon_prism.push_back({std::cos(a), std::sin(a), layer * 2.0});
        }
    }
    const double pentagon_area = 2.5 * std::sin(2 * M_PI / 5);
    const std::vector<Case> cases = {
        {CellType::kTetra, {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, 1.0 / 6, 1},
        {CellType::kHexahedron, cube, 1.0, 6},
        {CellType::kVoxel, voxel, 1.0, 6},
        {CellType::kWedge,
         {{0, 0, 0}, {0, 1, 0}, {1, 0, 0}, {0, 0, 1}, {0, 1, 1}, {1, 0, 1}},
         0.5,
         3},
        {CellType::kPyramid, {cube[0], cube[1], cube[2], cube[3], {0.5, 0.5, 1}}, 1.0 / 3, 2},
        {CellType::kQuadraticTetra, quadratic_tet, 1.0 / 6, 1},
        {CellType::kPentagonalPrism, pentagon_prism, 2 * pentagon_area, 0},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(std::string(cell_type_name(c.type)));
        TetrahedralizeReport report;
        auto mesh = tetrahedralize(single_cell(c.type, c.points), {}, &report);
        ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
        EXPECT_NEAR(mesh->real_volume(), c.volume, 1e-12);
        if (c.tets) {
            EXPECT_EQ(mesh->num_tets(), c.tets);
        }
        EXPECT_EQ(report.num_inverted_cells, 0u);
        EXPECT_EQ(report.num_quadratic_cells, is_quadratic(c.type) ? 1u : 0u);
    }
}

TEST(Tetrahedralize, CollapsedHexKeepsItsVolumeAndDropsFlatTets) {
    // A hex with its top face collapsed to an edge (a wedge in disguise), as at a grid's wall.
    UnstructuredMesh m;
    m.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {0, 1, 1}};
    m.add_cell(CellType::kHexahedron, {0, 1, 2, 3, 4, 4, 5, 5});
    TetrahedralizeReport report;
    auto mesh = tetrahedralize(m, {}, &report);
    ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
    EXPECT_NEAR(mesh->real_volume(), 0.5, 1e-12);
    EXPECT_EQ(report.num_degenerate_cells, 0u);
}

TEST(Tetrahedralize, FlatCellIsDroppedAndCounted) {
    UnstructuredMesh m;
    m.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {0, 0, 1}};
    m.add_cell(CellType::kTetra, {0, 1, 2, 3});  // all in z = 0
    m.add_cell(CellType::kTetra, {0, 1, 2, 4});
    TetrahedralizeReport report;
    auto mesh = tetrahedralize(m, {}, &report);
    ASSERT_TRUE(mesh.ok());
    EXPECT_EQ(report.num_degenerate_cells, 1u);
    EXPECT_EQ(mesh->num_tets(), 1u);
    EXPECT_EQ(mesh->source_cell(0), 1u);
}

TEST(Tetrahedralize, CellFieldsFollowTheirCellsAndPointFieldsTheirPoints) {
    MixedGridOptions o;
    o.nx = o.ny = o.nz = 2;
    UnstructuredMesh input = make_mixed_grid(o);
    std::vector<double> cell_values(input.num_cells());
    for (std::size_t c = 0; c < cell_values.size(); ++c) cell_values[c] = 10.0 * c;
    input.cell_fields.push_back(make_double_field("id", 1, cell_values));
    std::vector<float> xs;
    for (const Vec3& p : input.points) xs.push_back(static_cast<float>(p.x));
    input.point_fields.push_back(make_float_field("x", 1, xs));
    auto mesh = tetrahedralize(input);
    ASSERT_TRUE(mesh.ok());
    const Field* id = find_field(mesh->cell_fields(), "id");
    ASSERT_NE(id, nullptr);
    EXPECT_TRUE(id->is_double());
    for (CellId t = 0; t < mesh->num_tets(); ++t) {
        EXPECT_EQ(id->get(t), 10.0 * mesh->source_cell(t));
    }
    const Field* x = find_field(mesh->point_fields(), "x");
    ASSERT_NE(x, nullptr);
    EXPECT_FALSE(x->is_double());
    for (PointId p = 0; p < mesh->num_points(); ++p) {
        EXPECT_FLOAT_EQ(static_cast<float>(x->get(p)), static_cast<float>(mesh->point(p).x));
    }
}

}  // namespace
}  // namespace tr
