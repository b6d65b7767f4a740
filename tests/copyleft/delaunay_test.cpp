// Delaunay tetrahedralization (CGAL): validity, volume of the hull, duplicates, bad input.
#include <mesh/copyleft/delaunay.h>
#include <mesh/face_adjacency.h>

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace tr {
namespace {

// The 8 corners of [lo, hi]^3 then `num_interior` random points strictly inside.
UnstructuredMesh cube_cloud(std::uint32_t seed, std::size_t num_interior, double lo, double hi) {
    UnstructuredMesh cloud;
    for (int c = 0; c < 8; ++c) {
        cloud.points.emplace_back((c & 1) ? hi : lo, (c & 2) ? hi : lo, (c & 4) ? hi : lo);
    }
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(lo, hi);
    for (std::size_t i = 0; i < num_interior; ++i)
        cloud.points.emplace_back(u(rng), u(rng), u(rng));
    return cloud;
}

bool on_cube_face(const TetMesh& mesh, std::array<PointId, 3> face, double lo, double hi) {
    for (int axis = 0; axis < 3; ++axis) {
        for (double plane : {lo, hi}) {
            bool all = true;
            for (PointId p : face) all = all && mesh.point(p)[axis] == plane;
            if (all) return true;
        }
    }
    return false;
}

TEST(Delaunay, RandomPointsInACubeFillTheCube) {
    for (std::uint32_t seed = 1; seed <= 8; ++seed) {
        SCOPED_TRACE(seed);
        const double lo = -0.5 * seed;
        const double hi = 1.0 + 0.25 * seed;
        const UnstructuredMesh cloud = cube_cloud(seed, 200 * seed, lo, hi);
        DelaunayReport report;
        auto mesh = delaunay_tetrahedralize(cloud, &report);
        ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
        EXPECT_EQ(mesh->num_points(), cloud.points.size());
        EXPECT_EQ(report.num_duplicate_points, 0u);
        EXPECT_EQ(report.num_dropped_tets, 0u);
        EXPECT_EQ(report.num_tets, mesh->num_tets());
        double volume = 0;
        for (CellId t = 0; t < mesh->num_tets(); ++t) {
            const double v = mesh->tet_volume(t);
            ASSERT_GT(v, 0.0) << "tet " << t;
            volume += v;
        }
        const double cube = std::pow(hi - lo, 3);
        EXPECT_NEAR(volume, cube, 1e-9 * cube);
        // build_face_adjacency fails when three tets share a face.
        auto adjacency = build_face_adjacency(*mesh);
        ASSERT_TRUE(adjacency.ok()) << adjacency.error().to_string();
        double boundary_area = 0;
        for (const BoundaryFace& f : adjacency->boundary_faces) {
            const auto v = face_points(*mesh, f.tet, f.face);
            ASSERT_TRUE(on_cube_face(*mesh, v, lo, hi)) << "tet " << f.tet << " face " << f.face;
            boundary_area += 0.5 * glm::length(glm::cross(mesh->point(v[1]) - mesh->point(v[0]),
                                                          mesh->point(v[2]) - mesh->point(v[0])));
        }
        EXPECT_NEAR(boundary_area, 6 * std::pow(hi - lo, 2), 1e-9 * boundary_area);
        EXPECT_TRUE(check_convexity(*mesh, *adjacency).convex);
    }
}

TEST(Delaunay, GridPointsWithManyCosphericalTiesStillGiveAValidMesh) {
    UnstructuredMesh cloud;
    for (int i = 0; i < 6; ++i)
        for (int j = 0; j < 6; ++j)
            for (int k = 0; k < 6; ++k) cloud.points.emplace_back(i, j, k);
    auto mesh = delaunay_tetrahedralize(cloud);
    ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
    double volume = 0;
    for (CellId t = 0; t < mesh->num_tets(); ++t) volume += mesh->tet_volume(t);
    EXPECT_NEAR(volume, 125.0, 1e-9 * 125.0);
    EXPECT_TRUE(build_face_adjacency(*mesh).ok());
}

TEST(Delaunay, MergesDuplicatePointsAndCarriesFields) {
    UnstructuredMesh cloud = cube_cloud(7, 50, 0.0, 1.0);
    const std::size_t distinct = cloud.points.size();
    // Duplicates of points 3, 10 and 20 (twice) appended at the end, and one in between.
    for (std::size_t d : {3u, 10u, 20u, 20u}) cloud.points.push_back(cloud.points[d]);
    cloud.points.insert(cloud.points.begin() + 30, cloud.points[5]);  // becomes index 30
    const std::size_t n = cloud.points.size();
    std::vector<double> ids(n);
    std::vector<float> vectors(3 * n);
    for (std::size_t i = 0; i < n; ++i) {
        ids[i] = static_cast<double>(i);
        for (int c = 0; c < 3; ++c) vectors[3 * i + c] = static_cast<float>(i * 10 + c);
    }
    cloud.point_fields.push_back(make_double_field("id", 1, ids));
    cloud.point_fields.push_back(make_float_field("vec", 3, vectors));

    DelaunayReport report;
    auto mesh = delaunay_tetrahedralize(cloud, &report);
    ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
    EXPECT_EQ(report.num_input_points, n);
    EXPECT_EQ(report.num_duplicate_points, 5u);
    ASSERT_EQ(mesh->num_points(), distinct);
    // Distinct points keep their input order; each carries its own (first) values.
    const Field* id = find_field(mesh->point_fields(), "id");
    const Field* vec = find_field(mesh->point_fields(), "vec");
    ASSERT_NE(id, nullptr);
    ASSERT_NE(vec, nullptr);
    EXPECT_TRUE(id->is_double());
    EXPECT_FALSE(vec->is_double());
    for (std::size_t i = 0; i < mesh->num_points(); ++i) {
        const auto source = static_cast<std::size_t>(id->get(i));
        EXPECT_EQ(mesh->point(static_cast<PointId>(i)), cloud.points[source]);
        EXPECT_NE(source, 30u);  // the inserted duplicate of point 5 is merged away
        for (int c = 0; c < 3; ++c) EXPECT_EQ(vec->get(i, c), static_cast<double>(source * 10 + c));
        if (i > 0) {
            EXPECT_GT(source, static_cast<std::size_t>(id->get(i - 1)));
        }
    }
    double volume = 0;
    for (CellId t = 0; t < mesh->num_tets(); ++t) volume += mesh->tet_volume(t);
    EXPECT_NEAR(volume, 1.0, 1e-9);
    EXPECT_TRUE(build_face_adjacency(*mesh).ok());
}

void expect_invalid(const UnstructuredMesh& cloud, const std::string& needle) {
    auto mesh = delaunay_tetrahedralize(cloud);
    ASSERT_FALSE(mesh.ok());
    EXPECT_EQ(mesh.error().code, ErrorCode::kInvalidMesh);
    EXPECT_NE(mesh.error().to_string().find(needle), std::string::npos) << mesh.error().to_string();
    EXPECT_EQ(mesh.error().to_string().find('\n'), std::string::npos);
}

TEST(Delaunay, RejectsTooFewPoints) {
    UnstructuredMesh cloud;
    expect_invalid(cloud, "at least 4");
    cloud.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    expect_invalid(cloud, "at least 4");
    cloud.points.push_back({1, 0, 0});  // 4 points, 3 distinct
    expect_invalid(cloud, "at least 4");
}

TEST(Delaunay, RejectsCoplanarAndCollinearPoints) {
    UnstructuredMesh cloud;
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-1, 1);
    // A tilted plane through the origin: z = 0.5 x - 0.25 y, exactly representable.
    for (int i = 0; i < 40; ++i) {
        const double x = std::ldexp(std::round(std::ldexp(u(rng), 20)), -20);
        const double y = std::ldexp(std::round(std::ldexp(u(rng), 20)), -20);
        cloud.points.emplace_back(x, y, 0.5 * x - 0.25 * y);
    }
    expect_invalid(cloud, "coplanar");
    cloud.points.clear();
    for (int i = 0; i < 10; ++i) cloud.points.emplace_back(i, 2 * i, -i);
    expect_invalid(cloud, "collinear");
}

TEST(Delaunay, RejectsNonFinitePointsNamingThem) {
    UnstructuredMesh cloud = cube_cloud(1, 10, 0, 1);
    cloud.points[12].y = std::numeric_limits<double>::quiet_NaN();
    expect_invalid(cloud, "point 12");
    cloud.points[12].y = 0.5;
    cloud.points[4].z = std::numeric_limits<double>::infinity();
    expect_invalid(cloud, "point 4");
}

TEST(Delaunay, RejectsFieldsOfTheWrongSize) {
    UnstructuredMesh cloud = cube_cloud(1, 10, 0, 1);
    cloud.point_fields.push_back(make_float_field("short", 1, std::vector<float>(5)));
    auto mesh = delaunay_tetrahedralize(cloud);
    ASSERT_FALSE(mesh.ok());
    EXPECT_EQ(mesh.error().code, ErrorCode::kInvalidArgument);
    EXPECT_NE(mesh.error().message.find("short"), std::string::npos);
}

TEST(Delaunay, HundredThousandPoints) {
#if defined(__SANITIZE_ADDRESS__)
    const std::size_t n = 20000;  // ASan builds are about 25 times slower here
#else
    const std::size_t n = 100000;
#endif
    const UnstructuredMesh cloud = cube_cloud(42, n, 0, 1);
    DelaunayReport report;
    auto mesh = delaunay_tetrahedralize(cloud, &report);
    ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
    EXPECT_NEAR(mesh->real_volume(), 1.0, 1e-9);
    std::printf("delaunay: %zu points -> %zu tets in %.3f s\n", cloud.points.size(),
                report.num_tets, report.seconds);
    EXPECT_GT(report.seconds, 0.0);
}

}  // namespace
}  // namespace tr
