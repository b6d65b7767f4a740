// TetMesh validation, virtual tets, cell-to-point averaging, and rejected input.
#include <mesh/face_adjacency.h>
#include <mesh/point_data.h>
#include <mesh/tet_mesh.h>
#include <mesh/tetrahedralize.h>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace tr {
namespace {

std::vector<Vec3> two_tet_points() {
    return {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}};
}

TEST(TetMesh, FlipsNegativeTetsAndDropsDegenerateOnes) {
    TetRepairReport report;
    auto mesh = TetMesh::create(two_tet_points(),
                                {{0, 2, 1, 3},   // negative: flipped
                                 {1, 2, 3, 4},   // positive
                                 {0, 0, 1, 2}},  // repeated vertex: dropped
                                {}, {}, &report);
    ASSERT_TRUE(mesh.ok());
    EXPECT_EQ(report.num_reoriented, 1u);
    EXPECT_EQ(report.num_degenerate, 1u);
    ASSERT_EQ(mesh->num_tets(), 2u);
    EXPECT_NEAR(mesh->tet_volume(0), 1.0 / 6, 1e-15);
    EXPECT_GT(mesh->tet_volume(1), 0.0);
    EXPECT_EQ(mesh->source_cell(1), 1u);
}

TEST(TetMesh, RejectsOutOfRangeIndex) {
    auto mesh = TetMesh::create(two_tet_points(), {{0, 1, 2, 9}});
    ASSERT_FALSE(mesh.ok());
    EXPECT_EQ(mesh.error().code, ErrorCode::kInvalidMesh);
    EXPECT_NE(mesh.error().to_string().find("tet 0"), std::string::npos);
}

TEST(TetMesh, RejectsNonFinitePoints) {
    for (double bad :
         {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
        auto points = two_tet_points();
        points[3].y = bad;
        auto mesh = TetMesh::create(points, {{0, 1, 2, 3}});
        ASSERT_FALSE(mesh.ok());
        EXPECT_NE(mesh.error().to_string().find("point 3"), std::string::npos);
        EXPECT_EQ(mesh.error().to_string().find('\n'), std::string::npos);
    }
}

TEST(TetMesh, RejectsSourceCellsOfWrongLength) {
    auto mesh = TetMesh::create(two_tet_points(), {{0, 1, 2, 3}}, {0, 1});
    EXPECT_FALSE(mesh.ok());
}

TEST(TetMesh, VirtualTetsComeAfterRealOnesAndCanBeRemoved) {
    auto mesh = TetMesh::create(two_tet_points(), {{0, 1, 2, 3}});
    ASSERT_TRUE(mesh.ok());
    ASSERT_TRUE(mesh->add_point_field(make_float_field("s", 1, {1, 2, 3, 4, 5})).ok());
    ASSERT_TRUE(mesh->append_virtual({{2, 2, 2}}, {{1, 2, 3, 5}}).ok());
    EXPECT_EQ(mesh->num_tets(), 2u);
    EXPECT_EQ(mesh->num_real_tets(), 1u);
    EXPECT_TRUE(mesh->is_virtual(1));
    EXPECT_EQ(mesh->source_cell(1), kNoCell);
    EXPECT_EQ(mesh->point_fields()[0].num_tuples(), 6u);
    EXPECT_GT(mesh->tet_volume(1), 0.0);
    mesh->remove_virtual();
    EXPECT_EQ(mesh->num_tets(), 1u);
    EXPECT_EQ(mesh->num_points(), 5u);
    EXPECT_EQ(mesh->point_fields()[0].num_tuples(), 5u);
}

TEST(TetMesh, FieldSizesAreChecked) {
    auto mesh = TetMesh::create(two_tet_points(), {{0, 1, 2, 3}});
    ASSERT_TRUE(mesh.ok());
    EXPECT_FALSE(mesh->add_point_field(make_float_field("s", 1, {1, 2})).ok());
    EXPECT_FALSE(mesh->add_cell_field(make_float_field("c", 1, {1, 2})).ok());
    EXPECT_TRUE(mesh->add_cell_field(make_float_field("c", 1, {1})).ok());
    EXPECT_FALSE(mesh->add_cell_field(make_float_field("c", 1, {1})).ok());  // duplicate
}

TEST(PointData, CellToPointIsTheVolumeWeightedMean) {
    // Two tets sharing face (1, 2, 3); volumes 1/6 and 1/3.
    std::vector<Vec3> points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {2, 2, 2}};
    auto mesh = TetMesh::create(points, {{0, 1, 2, 3}, {1, 2, 3, 4}});
    ASSERT_TRUE(mesh.ok());
    const double v0 = mesh->tet_volume(0), v1 = mesh->tet_volume(1);
    ASSERT_GT(v1, v0);
    const Field point = cell_to_point(*mesh, make_double_field("c", 1, {3.0, 9.0}));
    EXPECT_DOUBLE_EQ(point.get(0), 3.0);
    EXPECT_DOUBLE_EQ(point.get(4), 9.0);
    EXPECT_NEAR(point.get(1), (3.0 * v0 + 9.0 * v1) / (v0 + v1), 1e-14);
    // A constant cell field stays constant, and the mean lies between the extremes.
    const Field constant = cell_to_point(*mesh, make_float_field("k", 1, {2.f, 2.f}));
    for (PointId p = 0; p < 5; ++p) EXPECT_FLOAT_EQ(static_cast<float>(constant.get(p)), 2.f);
}

TEST(PointData, PointScalarPicksComponentsMagnitudesAndCellData) {
    auto mesh = TetMesh::create(two_tet_points(), {{0, 1, 2, 3}});
    ASSERT_TRUE(mesh.ok());
    std::vector<float> v;
    for (int p = 0; p < 5; ++p) v.insert(v.end(), {3.f, 4.f, float(p)});
    ASSERT_TRUE(mesh->add_point_field(make_float_field("v", 3, v)).ok());
    ASSERT_TRUE(mesh->add_cell_field(make_float_field("c", 1, {7.f})).ok());
    auto mag = point_scalar(*mesh, "v", -1);
    ASSERT_TRUE(mag.ok());
    EXPECT_FLOAT_EQ((*mag)[0], 5.f);
    auto z = point_scalar(*mesh, "v", 2);
    ASSERT_TRUE(z.ok());
    EXPECT_FLOAT_EQ((*z)[4], 4.f);
    auto c = point_scalar(*mesh, "c");
    ASSERT_TRUE(c.ok());
    EXPECT_FLOAT_EQ((*c)[1], 7.f);
    auto missing = point_scalar(*mesh, "nope");
    ASSERT_FALSE(missing.ok());
    EXPECT_NE(missing.error().message.find("v, c (cell)"), std::string::npos);
    EXPECT_FALSE(point_scalar(*mesh, "v", 3).ok());
}

TEST(FaceAdjacency, ThreeTetsOnOneFaceIsAnError) {
    std::vector<Vec3> points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, 0, -1}, {1, 1, 1}};
    auto mesh = TetMesh::create(points, {{0, 1, 2, 3}, {0, 2, 1, 4}, {0, 1, 2, 5}});
    ASSERT_TRUE(mesh.ok());
    auto adjacency = build_face_adjacency(*mesh);
    ASSERT_FALSE(adjacency.ok());
    EXPECT_EQ(adjacency.error().code, ErrorCode::kInvalidMesh);
}

TEST(FaceAdjacency, SingleTetIsConvexWithFourBoundaryFaces) {
    auto mesh = TetMesh::create(two_tet_points(), {{0, 1, 2, 3}});
    ASSERT_TRUE(mesh.ok());
    auto adjacency = build_face_adjacency(*mesh);
    ASSERT_TRUE(adjacency.ok());
    EXPECT_EQ(adjacency->boundary_faces.size(), 4u);
    EXPECT_TRUE(check_convexity(*mesh, *adjacency).convex);
    // Outward faces: the opposite vertex lies behind each face's plane.
    for (int k = 0; k < 4; ++k) {
        const auto f = face_points(*mesh, 0, k);
        EXPECT_LT(orient3d(mesh->point(f[0]), mesh->point(f[1]), mesh->point(f[2]),
                           mesh->point(mesh->tet(0)[k])),
                  0.0);
    }
}

TEST(BadInput, TetrahedralizeRejectsBrokenCells) {
    UnstructuredMesh m;
    m.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    m.add_cell(CellType::kTetra, {0, 1, 2, 7});
    auto r = tetrahedralize(m);
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.error().to_string().find("cell 0"), std::string::npos);

    UnstructuredMesh wrong_count;
    wrong_count.points = m.points;
    wrong_count.add_cell(CellType::kHexahedron, {0, 1, 2, 3});
    EXPECT_FALSE(tetrahedralize(wrong_count).ok());

    UnstructuredMesh polyhedron;
    polyhedron.points = m.points;
    polyhedron.add_cell(static_cast<CellType>(42), {0, 1, 2, 3});
    auto unsupported = tetrahedralize(polyhedron);
    ASSERT_FALSE(unsupported.ok());
    EXPECT_EQ(unsupported.error().code, ErrorCode::kUnsupported);
    TetrahedralizeOptions skip;
    skip.skip_unsupported = true;
    polyhedron.add_cell(CellType::kTetra, {0, 1, 2, 3});
    TetrahedralizeReport report;
    auto skipped = tetrahedralize(polyhedron, skip, &report);
    ASSERT_TRUE(skipped.ok());
    EXPECT_EQ(report.num_skipped_cells, 1u);

    UnstructuredMesh cloud;
    cloud.points = m.points;
    EXPECT_EQ(tetrahedralize(cloud).error().code, ErrorCode::kUnsupported);
    EXPECT_FALSE(tetrahedralize(UnstructuredMesh{}).ok());

    UnstructuredMesh nan_point;
    nan_point.points = m.points;
    nan_point.points[2].x = std::nan("");
    nan_point.add_cell(CellType::kTetra, {0, 1, 2, 3});
    EXPECT_FALSE(tetrahedralize(nan_point).ok());
}

TEST(BadInput, MakeUnstructuredMeshChecksArrays) {
    EXPECT_FALSE(make_unstructured_mesh({0, 0}, {}, {}, {}).ok());
    EXPECT_FALSE(make_unstructured_mesh({0, 0, 0, 1, 0, 0}, {0, 1, 0}, {0, 4}, {10}).ok());
    auto ok = make_unstructured_mesh({0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1}, {0, 1, 2, 3}, {}, {10});
    ASSERT_TRUE(ok.ok()) << ok.error().to_string();
    auto mesh = tetrahedralize(*ok);
    ASSERT_TRUE(mesh.ok());
    EXPECT_NEAR(mesh->real_volume(), 1.0 / 6, 1e-15);
}

}  // namespace
}  // namespace tr
