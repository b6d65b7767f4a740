// Flow volumes against closed forms: volumes of uniform and rotating flows, dye mass in an
// expanding flow, order-independent rendering.
#include <core/camera.h>
#include <flowvol/flow_volume.h>
#include <mesh/tetrahedralize.h>
#include <project/cpu_renderer.h>
#include <tests/mesh/mixed_grid.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

namespace tr {
namespace {

struct Domain {
    TetMesh mesh;
    FaceAdjacency adjacency;
};

// [-2, 2]^3 as a mixed grid, with a velocity field v(p).
Domain box_domain(Vec3 (*velocity)(const Vec3&)) {
    testing::MixedGridOptions o;
    o.nx = o.ny = o.nz = 8;
    o.linear = glm::dmat3(0.5);
    o.offset = Vec3(-2.0);
    Domain d;
    d.mesh = tetrahedralize(testing::make_mixed_grid(o)).value();
    d.adjacency = build_face_adjacency(d.mesh).value();
    std::vector<float> v;
    for (const Vec3& p : d.mesh.points()) {
        const Vec3 u = velocity(p);
        v.insert(v.end(), {float(u.x), float(u.y), float(u.z)});
    }
    EXPECT_TRUE(d.mesh.add_point_field(make_float_field("v", 3, v)).ok());
    return d;
}

const Field& velocity(const Domain& d) { return d.mesh.point_fields()[0]; }

double layer_volume(const FlowVolume& fv, std::size_t layer) {
    const std::size_t begin = layer == 0 ? 0 : fv.layer_tets[layer - 1];
    double v = 0;
    for (std::size_t t = begin; t < fv.layer_tets[layer]; ++t) v += fv.mesh.tet_volume(CellId(t));
    return v;
}

TEST(FlowVolume, UniformFlowFillsABox) {
    const Domain d = box_domain([](const Vec3&) { return Vec3(1, 0, 0); });
    DyeSeed seed;
    seed.center = Vec3(-1.5, 0.1, -0.2);
    seed.width = 1.0;
    seed.height = 1.2;
    seed.resolution = 8;
    FlowVolumeOptions options;
    options.steps = 10;
    options.dt = 0.2;
    auto fv = grow_flow_volume(d.mesh, d.adjacency, velocity(d), seed, options);
    ASSERT_TRUE(fv.ok()) << fv.error().to_string();
    const double expected = 1.0 * 1.2 * 1.0 * 0.2 * 10;  // area x speed x time
    EXPECT_NEAR(fv->mesh.real_volume(), expected, 1e-9 * expected);
    EXPECT_EQ(fv->layer_tets.size(), 10u);
    EXPECT_EQ(fv->particles_stopped, 0u);
    for (std::size_t k = 0; k < 10; ++k) EXPECT_NEAR(layer_volume(*fv, k), expected / 10, 1e-9);
}

TEST(FlowVolume, UniformFlowIsClippedAtTheBoundary) {
    const Domain d = box_domain([](const Vec3&) { return Vec3(1, 0, 0); });
    DyeSeed seed;
    seed.center = Vec3(1.0, 0, 0);
    seed.width = seed.height = 0.5;
    seed.resolution = 4;
    FlowVolumeOptions options;
    options.steps = 10;
    options.dt = 0.25;  // would reach x = 3.5: the domain ends at 2
    auto fv = grow_flow_volume(d.mesh, d.adjacency, velocity(d), seed, options);
    ASSERT_TRUE(fv.ok()) << fv.error().to_string();
    EXPECT_NEAR(fv->mesh.real_volume(), 0.25 * 1.0, 1e-9);
    EXPECT_EQ(fv->particles_stopped, 25u);
}

TEST(FlowVolume, RigidRotationConservesEachLayersVolume) {
    const Domain d = box_domain([](const Vec3& p) { return Vec3(-p.y, p.x, 0); });
    DyeSeed seed;
    seed.center = Vec3(1.0, 0, 0.1);
    seed.width = seed.height = 0.6;
    seed.resolution = 12;
    FlowVolumeOptions options;
    options.steps = 40;
    options.dt = 0.05;
    auto fv = grow_flow_volume(d.mesh, d.adjacency, velocity(d), seed, options);
    ASSERT_TRUE(fv.ok()) << fv.error().to_string();
    const double first = layer_volume(*fv, 0);
    for (std::size_t k = 1; k < fv->layer_tets.size(); ++k) {
        EXPECT_NEAR(layer_volume(*fv, k), first, 0.01 * first) << k;
    }
}

TEST(FlowVolume, ExpandingFlowConservesDyeMass) {
    const Domain d = box_domain([](const Vec3& p) { return Vec3(p.x + 1.8, 0, 0); });
    DyeSeed seed;
    seed.center = Vec3(-1.0, 0, 0);
    seed.width = seed.height = 0.8;
    seed.resolution = 6;
    FlowVolumeOptions options;
    options.steps = 8;
    options.dt = 0.1;
    options.compressible = true;
    auto fv = grow_flow_volume(d.mesh, d.adjacency, velocity(d), seed, options);
    ASSERT_TRUE(fv.ok()) << fv.error().to_string();
    const Field* c = find_field(fv->mesh.cell_fields(), "concentration");
    ASSERT_NE(c, nullptr);
    std::vector<double> mass(fv->layer_tets.size(), 0.0), volume(mass.size(), 0.0);
    for (std::size_t k = 0, t = 0; k < mass.size(); ++k) {
        for (; t < fv->layer_tets[k]; ++t) {
            mass[k] += c->get(t) * fv->mesh.tet_volume(CellId(t));
            volume[k] += fv->mesh.tet_volume(CellId(t));
        }
    }
    for (std::size_t k = 1; k < mass.size(); ++k) {
        EXPECT_GT(volume[k], volume[k - 1] * 1.05);  // the flow expands the layers
        EXPECT_NEAR(mass[k], mass[0], 0.01 * mass[0]) << k;
    }
}

TEST(FlowVolume, BadSeedsAreErrors) {
    const Domain d = box_domain([](const Vec3&) { return Vec3(1, 0, 0); });
    DyeSeed outside;
    outside.center = Vec3(9, 9, 9);
    EXPECT_FALSE(grow_flow_volume(d.mesh, d.adjacency, velocity(d), outside).ok());
    DyeSeed bad;
    bad.resolution = 0;
    EXPECT_FALSE(grow_flow_volume(d.mesh, d.adjacency, velocity(d), bad).ok());
    const Domain still = box_domain([](const Vec3&) { return Vec3(0.0); });
    EXPECT_FALSE(grow_flow_volume(still.mesh, still.adjacency, velocity(still), DyeSeed{}).ok());
}

TEST(FlowVolume, RendersTheSameInAnyOrder) {
    const Domain d = box_domain([](const Vec3& p) { return Vec3(1.0, 0.3 * p.z, -0.3 * p.y); });
    DyeSeed seed;
    seed.center = Vec3(-1.6, 0, 0);
    seed.width = seed.height = 1.0;
    seed.resolution = 6;
    FlowVolumeOptions options;
    options.steps = 12;
    options.dt = 0.2;
    auto fv = grow_flow_volume(d.mesh, d.adjacency, velocity(d), seed, options);
    ASSERT_TRUE(fv.ok());
    const std::vector<float> scalar(fv->mesh.num_points(), 1.0f);
    const TransferFunction tf =
        TransferFunction::create({{1, {0.9, 0.9, 1.0}}}, {{1, 0.3}}, 1.0).value();
    const SegmentShader shader(tf, Integrator::kPreintegrated, longest_edge(fv->mesh));
    const CameraFrame frame(framing_camera(fv->mesh.bounds(), Vec3(0.3, -1, 0.5)), 96, 72);
    std::vector<CellId> order(fv->mesh.num_tets());
    std::iota(order.begin(), order.end(), CellId{0});
    RenderInputs in;
    in.mesh = &fv->mesh;
    in.scalar = scalar;
    in.shader = &shader;
    in.camera = &frame;
    in.order = order;
    const Image first = render_projected_tetrahedra(in);
    std::mt19937 rng(4);
    for (int trial = 0; trial < 3; ++trial) {
        std::shuffle(order.begin(), order.end(), rng);
        in.order = order;
        const Image again = render_projected_tetrahedra(in);
        EXPECT_LT(max_abs_difference(first, again), 1e-6);
    }
}

}  // namespace
}  // namespace tr
