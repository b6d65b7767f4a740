// Convexification: the union of real and virtual tets is a conforming mesh of the box.
#include <mesh/copyleft/convexify.h>
#include <mesh/copyleft/cylinder_demo.h>
#include <mesh/face_adjacency.h>
#include <mesh/tetrahedralize.h>
#include <tests/support/mixed_grid.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace tr {
namespace {

using testing::make_mixed_grid;
using testing::MixedGridOptions;

TetMesh grid_mesh(MixedGridOptions options) {
    auto mesh = tetrahedralize(make_mixed_grid(options));
    EXPECT_TRUE(mesh.ok()) << mesh.error().to_string();
    return std::move(mesh).value();
}

// An L: a 4 x 4 x 2 block without its 2 x 2 x 2 corner.
TetMesh l_block(std::uint32_t seed) {
    MixedGridOptions o;
    o.nx = 4;
    o.ny = 4;
    o.nz = 2;
    o.seed = seed;
    o.skip_box = [](int i, int j, int) { return i >= 2 && j >= 2; };
    return grid_mesh(o);
}

// A square ring (genus 1): a 4 x 4 x 1 slab without its 2 x 2 middle.
TetMesh ring(std::uint32_t seed) {
    MixedGridOptions o;
    o.nx = 4;
    o.ny = 4;
    o.nz = 1;
    o.seed = seed;
    o.offset = Vec3(10.0, -3.0, 0.5);
    o.skip_box = [](int i, int j, int) { return i >= 1 && i <= 2 && j >= 1 && j <= 2; };
    return grid_mesh(o);
}

// Two blocks that do not touch.
TetMesh two_blocks(std::uint32_t seed) {
    MixedGridOptions o;
    o.nx = 5;
    o.ny = 2;
    o.nz = 2;
    o.seed = seed;
    o.skip_box = [](int i, int, int) { return i == 2; };
    return grid_mesh(o);
}

// Checks everything convexify promises; returns the number of virtual tets.
std::size_t expect_convexified(TetMesh mesh, const ConvexifyOptions& options = {}) {
    const TetMesh original = mesh;
    auto adjacency = build_face_adjacency(mesh);
    EXPECT_TRUE(adjacency.ok());
    EXPECT_FALSE(check_convexity(mesh, *adjacency).convex);
    auto report = convexify(mesh, *adjacency, options);
    EXPECT_TRUE(report.ok()) << report.error().to_string();
    if (!report.ok()) return 0;
    EXPECT_FALSE(report->already_convex);
    EXPECT_GT(report->num_virtual_tets, 0u);
    EXPECT_EQ(report->num_virtual_tets, mesh.num_virtual_tets());

    // The real part is unchanged.
    EXPECT_EQ(mesh.num_real_tets(), original.num_tets());
    EXPECT_TRUE(std::equal(original.tets().begin(), original.tets().end(), mesh.tets().begin()));
    EXPECT_TRUE(
        std::equal(original.points().begin(), original.points().end(), mesh.points().begin()));
    for (std::size_t f = 0; f < original.point_fields().size(); ++f) {
        EXPECT_EQ(mesh.point_fields()[f].num_tuples(), mesh.num_points());
    }

    // Real + virtual volume is the box's.
    const Bounds3 b = original.bounds();
    const Vec3 s = b.size();
    const double margin = options.box_margin * std::max({s.x, s.y, s.z});
    const Vec3 lo = b.lo - Vec3(margin);
    const Vec3 hi = b.hi + Vec3(margin);
    const Vec3 box = hi - lo;
    double volume = 0;
    for (CellId t = 0; t < mesh.num_tets(); ++t) {
        const double v = mesh.tet_volume(t);
        EXPECT_GT(v, 0.0) << "tet " << t;
        volume += v;
    }
    EXPECT_NEAR(volume, box.x * box.y * box.z, 1e-9 * box.x * box.y * box.z);

    // The union is conforming and its boundary is the box's 12 triangles.
    auto union_adjacency = build_face_adjacency(mesh);
    EXPECT_TRUE(union_adjacency.ok());
    if (!union_adjacency.ok()) return 0;
    EXPECT_EQ(union_adjacency->boundary_faces.size(), 12u);
    for (const BoundaryFace& f : union_adjacency->boundary_faces) {
        EXPECT_TRUE(mesh.is_virtual(f.tet));
        const auto v = face_points(mesh, f.tet, f.face);
        bool on_box = false;
        for (int axis = 0; axis < 3; ++axis) {
            for (double plane : {lo[axis], hi[axis]}) {
                bool all = true;
                for (PointId p : v) all = all && mesh.point(p)[axis] == plane;
                on_box = on_box || all;
            }
        }
        EXPECT_TRUE(on_box) << "tet " << f.tet << " face " << f.face;
    }
    // ...and it is convex (as a mesh whose tets are all real).
    auto all_real = TetMesh::create(mesh.points(), mesh.tets(), {}, {.degenerate_tolerance = 0});
    EXPECT_TRUE(all_real.ok());
    if (!all_real.ok()) return 0;
    EXPECT_EQ(all_real->num_tets(), mesh.num_tets());
    auto all_real_adjacency = build_face_adjacency(*all_real);
    EXPECT_TRUE(all_real_adjacency.ok());
    EXPECT_TRUE(check_convexity(*all_real, *all_real_adjacency).convex);
    return report->num_virtual_tets;
}

TEST(Convexify, LShapedBlock) {
    for (std::uint32_t seed = 1; seed <= 5; ++seed) {
        SCOPED_TRACE(seed);
        expect_convexified(l_block(seed));
    }
}

TEST(Convexify, Ring) {
    for (std::uint32_t seed = 1; seed <= 5; ++seed) {
        SCOPED_TRACE(seed);
        expect_convexified(ring(seed));
    }
}

TEST(Convexify, LargerMargin) {
    ConvexifyOptions options;
    options.box_margin = 0.5;
    expect_convexified(ring(9), options);
}

TEST(Convexify, TwoComponentsGetAHoleEach) {
    TetMesh mesh = two_blocks(3);
    auto adjacency = build_face_adjacency(mesh);
    ASSERT_TRUE(adjacency.ok());
    const TetMesh copy = mesh;
    auto report = convexify(mesh, *adjacency);
    ASSERT_TRUE(report.ok()) << report.error().to_string();
    EXPECT_EQ(report->num_components, 2u);
    expect_convexified(copy);
}

TEST(Convexify, CylinderDemo) {
    auto demo = make_cylinder_demo({.target_tets = 5000});
    ASSERT_TRUE(demo.ok()) << demo.error().to_string();
    const std::size_t num_virtual = expect_convexified(*demo);
    std::printf("convexify: demo of %zu tets -> %zu virtual tets\n", demo->num_tets(), num_virtual);
}

TEST(Convexify, ConvexMeshIsLeftAlone) {
    MixedGridOptions o;
    o.nx = o.ny = o.nz = 3;
    TetMesh mesh = grid_mesh(o);
    auto adjacency = build_face_adjacency(mesh);
    ASSERT_TRUE(adjacency.ok());
    auto report = convexify(mesh, *adjacency);
    ASSERT_TRUE(report.ok()) << report.error().to_string();
    EXPECT_TRUE(report->already_convex);
    EXPECT_EQ(report->num_virtual_tets, 0u);
    EXPECT_EQ(report->num_components, 1u);
    EXPECT_EQ(mesh.num_virtual_tets(), 0u);
}

TEST(Convexify, IntersectingBoundaryIsAnErrorAndLeavesTheMeshAlone) {
    // Two blocks that overlap without sharing faces: their boundaries cross.
    MixedGridOptions o;
    o.nx = o.ny = o.nz = 2;
    const TetMesh a = grid_mesh(o);
    o.offset = Vec3(1.1, 0.7, 0.3);
    o.seed = 2;
    const TetMesh b = grid_mesh(o);
    std::vector<Vec3> points = a.points();
    points.insert(points.end(), b.points().begin(), b.points().end());
    std::vector<Tet> tets = a.tets();
    for (Tet tet : b.tets()) {
        for (PointId& p : tet) p += static_cast<PointId>(a.num_points());
        tets.push_back(tet);
    }
    auto mesh = TetMesh::create(points, tets);
    ASSERT_TRUE(mesh.ok());
    auto adjacency = build_face_adjacency(*mesh);
    ASSERT_TRUE(adjacency.ok());
    auto report = convexify(*mesh, *adjacency);
    ASSERT_FALSE(report.ok());
    std::printf("convexify of crossing boundaries: %s\n", report.error().to_string().c_str());
    EXPECT_EQ(mesh->num_virtual_tets(), 0u);
    EXPECT_EQ(mesh->num_points(), points.size());
}

TEST(Convexify, BadCallsAreErrorsAndLeaveTheMeshAlone) {
    TetMesh mesh = l_block(1);
    auto adjacency = build_face_adjacency(mesh);
    ASSERT_TRUE(adjacency.ok());
    auto bad_margin = convexify(mesh, *adjacency, {.box_margin = 0.0});
    ASSERT_FALSE(bad_margin.ok());
    EXPECT_EQ(bad_margin.error().code, ErrorCode::kInvalidArgument);

    FaceAdjacency other = *adjacency;
    other.neighbors.pop_back();
    auto bad_adjacency = convexify(mesh, other);
    ASSERT_FALSE(bad_adjacency.ok());
    EXPECT_EQ(bad_adjacency.error().code, ErrorCode::kInvalidArgument);
    EXPECT_EQ(mesh.num_virtual_tets(), 0u);

    ASSERT_TRUE(convexify(mesh, *adjacency).ok());
    auto union_adjacency = build_face_adjacency(mesh);
    ASSERT_TRUE(union_adjacency.ok());
    auto twice = convexify(mesh, *union_adjacency);
    ASSERT_FALSE(twice.ok());
    EXPECT_NE(twice.error().message.find("already has"), std::string::npos);
}

}  // namespace
}  // namespace tr
