// Inputs fuzz_mesh_pipeline (fuzz/, docs/fuzzing.md) found in the way from garbage points and
// cells to a picture, each pinned here with the property it broke.
#include <mesh/face_adjacency.h>
#include <mesh/tet_mesh.h>
#include <mesh/tetrahedralize.h>
#include <mesh/unstructured_mesh.h>
#include <project/segment_shader.h>
#include <project/transfer_function.h>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

namespace tr {
namespace {

// Two unit tets sharing the face (1, 2, 3), around `origin`; the second copy of the shared
// face's corners moved by `jitter` (x), so that only a tolerant merge joins them.
UnstructuredMesh two_tets(const Vec3& origin, double jitter) {
    UnstructuredMesh mesh;
    const std::vector<Vec3> corners = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}};
    for (const Vec3& c : corners) mesh.points.push_back(origin + c);
    for (int k = 1; k <= 3; ++k) mesh.points.push_back(origin + corners[k] + Vec3(jitter, 0, 0));
    mesh.add_cell(CellType::kTetra, {0, 1, 2, 3});
    mesh.add_cell(CellType::kTetra, {5, 6, 7, 4});
    return mesh;
}

TEST(MeshFuzzFindings, TolerantMergeFarFromTheOrigin) {
    // fuzz_mesh_pipeline, first run: with a merge tolerance, the hash of a point's cube cast
    // coordinate / radius to int64 (undefined beyond 2^63; UBSan: "5.07e+299 is outside the
    // range of representable values of type 'long'") and multiplied it in signed arithmetic
    // (overflowing from 1.2e11 cubes on). Coordinates of 1e6 with unit edges and a tolerance of
    // 1e-6 (geographic coordinates, --merge-tolerance 1e-6) already overflowed. The cube index
    // is now clamped and hashed unsigned. A normal build happened to merge right before (x86
    // wraps); the sanitizer builds (TETRENDER_SANITIZE, the fuzz build) stopped here.
    struct Case {
        Vec3 origin;
        double jitter, tolerance;
    };
    for (const Case& c : {Case{Vec3(1e6, -1e6, 1e6), 1e-8, 1e-6},
                          Case{Vec3(1e7, 1e7, -1e7), 0.0, 1e-12}, Case{Vec3(0.0), 1e-8, 1e-6}}) {
        SCOPED_TRACE(c.origin.x);
        TetrahedralizeOptions options;
        options.merge_tolerance = c.tolerance;
        TetrahedralizeReport report;
        auto mesh = tetrahedralize(two_tets(c.origin, c.jitter), options, &report);
        ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
        EXPECT_EQ(report.num_merged_points, 3u);
        ASSERT_EQ(mesh.value().num_tets(), 2u);
        auto adjacency = build_face_adjacency(mesh.value());
        ASSERT_TRUE(adjacency.ok());
        EXPECT_EQ(adjacency.value().boundary_faces.size(), 6u);  // one face shared of 8
    }
}

TEST(MeshFuzzFindings, FlippedTetIsPositiveOrDropped) {
    // fuzz_mesh_pipeline, fourth run: with degenerate_tolerance 0 (what Delaunay meshes use), a
    // tet whose last two points coincide had orient3d -2^393 (rounding of a zero determinant
    // of coordinates near 1e66), was flipped, and orient3d of the flipped tet was -2^393 too: a
    // mesh with a negative tet, against tet_mesh.h's convention. A tet whose flip is not
    // positive is now dropped as degenerate.
    const Vec3 far(-0x1.dcdcdcdcdcdcdp+221, -0x1.dcdcdcdcdcdcdp+221, -0x1.dcdcdcdcdcdcdp+221);
    std::vector<Vec3> points = {Vec3(0, 0, 0), Vec3(-4, 0x1.d00001d040405p-1011, 1), far, far};
    TetMeshCreateOptions options;
    options.degenerate_tolerance = 0.0;
    TetRepairReport report;
    auto mesh = TetMesh::create(points, {{0, 1, 3, 2}, {0, 1, 2, 3}}, {}, options, &report);
    ASSERT_TRUE(mesh.ok());
    for (const Tet& t : mesh.value().tets()) {
        EXPECT_GT(orient3d(points[t[0]], points[t[1]], points[t[2]], points[t[3]]), 0.0);
    }
    EXPECT_EQ(mesh.value().num_tets() + report.num_degenerate, 2u);
    // A plain negative tet is still flipped and kept.
    auto flipped = TetMesh::create({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, {{0, 2, 1, 3}}, {},
                                   options, &report);
    ASSERT_TRUE(flipped.ok());
    EXPECT_EQ(flipped.value().num_tets(), 1u);
    EXPECT_EQ(report.num_reoriented, 1u);
}

TEST(MeshFuzzFindings, TransferFunctionOfNanScalar) {
    // fuzz_mesh_pipeline, second run: the exp-texture projection of a cell with coordinates near
    // 1e300 interpolated a NaN front scalar; TransferFunction::opacity(NaN) took upper_bound's
    // end as the upper control point and read past the array (ASan: heap-buffer-overflow in
    // piecewise_linear). A NaN scalar now reads the first control point.
    auto tf = TransferFunction::create({{0, Vec3(0.2, 0.4, 0.6)}, {1, Vec3(1, 1, 1)}},
                                       {{0, 0.25}, {1, 0.75}}, 1.0);
    ASSERT_TRUE(tf.ok());
    const double nan = std::numeric_limits<double>::quiet_NaN();
    EXPECT_EQ(tf.value().opacity(nan), 0.25);
    EXPECT_EQ(tf.value().color(nan), Vec3(0.2, 0.4, 0.6));
    EXPECT_TRUE(std::isfinite(tf.value().extinction(nan)));
}

TEST(MeshFuzzFindings, ExpTextureOfHugeEdgesAndExtinctions) {
    // fuzz_mesh_pipeline, fifth run: the exp texture's row index v / kappa_max was inf / inf =
    // NaN, cast to int (UBSan; a read far outside the table in a normal build) when a unit
    // distance of 1e-320 made the largest extinction overflow; and a mesh with coordinates
    // beyond 1e154 has a longest edge of inf (its square overflows), which made the table's
    // lengths inf * 0 = NaN. Both are now integrated directly (inf extinction) or tabled up to
    // the largest double (inf edge): finite colours, opacity in [0, 1].
    auto thick = TransferFunction::create({{0, Vec3(1, 0.5, 0)}, {1, Vec3(0, 0.5, 1)}},
                                          {{0, 0.5}, {1, 0.9}}, 1e-320);
    auto plain = TransferFunction::create({{0, Vec3(1, 0.5, 0)}, {1, Vec3(0, 0.5, 1)}},
                                          {{0, 0.5}, {1, 0.9}}, 1.0);
    // Extinctions near the largest double (-ln(0.1) / 2.3e-308 = 1.0e308): their sum, and the
    // texture's kappa_max * j, overflowed to inf (fuzz_mesh_pipeline, sixth run: NaN pixels).
    auto huge = TransferFunction::create({{0, Vec3(1, 0.5, 0)}, {1, Vec3(0, 0.5, 1)}},
                                         {{0, 0.5}, {1, 0.9}}, 2.3e-308);
    ASSERT_TRUE(huge.ok());
    ASSERT_TRUE(thick.ok());
    ASSERT_TRUE(plain.ok());
    const double inf = std::numeric_limits<double>::infinity();
    struct Case {
        const TransferFunction* tf;
        double max_length, length;
    };
    for (const Case& c : {Case{&thick.value(), 2.0, 1.0}, Case{&huge.value(), 2.0, 1.0},
                          Case{&huge.value(), 2.0, 1e-300}, Case{&plain.value(), inf, 1.0},
                          Case{&plain.value(), inf, 1e200}, Case{&plain.value(), inf, 1e-3}}) {
        SCOPED_TRACE(c.max_length);
        const SegmentShader shader(*c.tf, Integrator::kExpTexture, c.max_length);
        for (double s : {0.0, 0.3, 1.0}) {
            const ShadedSegment seg = shader.shade(s, 1.0 - s, c.length);
            EXPECT_TRUE(seg.alpha >= 0.0f && seg.alpha <= 1.0f) << seg.alpha;
            for (int k = 0; k < 3; ++k) EXPECT_TRUE(std::isfinite(seg.color[k])) << seg.color[k];
        }
    }
}

TEST(MeshFuzzFindings, SegmentLongerThanAFloat) {
    // fuzz_mesh_pipeline, seventh run: the default (preintegrated) integrator took the optical
    // depth in float: a segment longer than 3.4e38 (a mesh with coordinates near 1e39) gave
    // tau = inf and r = tau / (1 + tau) = NaN, cast to int: a read outside the mean-colour
    // table (UBSan; garbage or a crash in a normal build). r is now 1 there (infinitely thick:
    // the colour at the front), as in the directly integrated cells.
    auto tf = TransferFunction::create({{0, Vec3(1, 0.5, 0)}, {1, Vec3(0, 0.5, 1)}},
                                       {{0, 0.1}, {1, 0.2}}, 1.0);
    ASSERT_TRUE(tf.ok());
    for (Integrator integrator :
         {Integrator::kPreintegrated, Integrator::kExact, Integrator::kExpTexture}) {
        const SegmentShader shader(tf.value(), integrator, 1.0);
        for (double length : {1e39, 1e300, std::numeric_limits<double>::infinity()}) {
            SCOPED_TRACE(length);
            const ShadedSegment seg = shader.shade(0.25, 0.75, length);
            EXPECT_NEAR(seg.alpha, 1.0f, 1e-6f);
            // The colour at the front (0.25): opaque at once.
            EXPECT_NEAR(seg.color[0], 0.75f, 0.01f);
            EXPECT_NEAR(seg.color[2], 0.25f, 0.01f);
        }
    }
}

TEST(MeshFuzzFindings, ClearSegmentOfInfiniteLength) {
    // fuzz_mesh_pipeline, eighth run: the exact integrator's step count was ceil(0 * inf) = NaN
    // for a clear (zero-extinction) piece of infinite length, cast to int (UBSan), and each
    // step's opacity 1 - exp(-0 * inf) NaN. A clear piece now absorbs nothing, however long.
    auto clear = TransferFunction::create({{0, Vec3(1, 0.5, 0)}, {1, Vec3(0, 0.5, 1)}},
                                          {{0, 0.0}, {0.5, 0.0}, {1, 0.3}}, 1.0);
    ASSERT_TRUE(clear.ok());
    const SegmentShader shader(clear.value(), Integrator::kExact, 1.0);
    const double inf = std::numeric_limits<double>::infinity();
    ShadedSegment seg = shader.shade(0.0, 0.25, inf);
    EXPECT_EQ(seg.alpha, 0.0f);
    EXPECT_EQ(seg.color, Vec3f(0.0f));
    // Clear in front, then absorbing: opaque, the colour where the extinction starts.
    seg = shader.shade(0.0, 1.0, inf);
    EXPECT_TRUE(std::isfinite(seg.alpha) && seg.alpha > 0.99f) << seg.alpha;
    for (int k = 0; k < 3; ++k) EXPECT_TRUE(std::isfinite(seg.color[k])) << seg.color[k];
}

}  // namespace
}  // namespace tr
