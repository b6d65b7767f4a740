// Flow volumes against closed forms: volumes of uniform, rotating, straining and ABC flows,
// dye mass and concentration in an expanding flow, unsteady flow, adaptive subdivision,
// order-independent rendering.
#include <core/camera.h>
#include <core/image.h>
#include <flowvol/flow_volume.h>
#include <mesh/tetrahedralize.h>
#include <project/cpu_renderer.h>
#include <tests/support/mixed_grid.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <random>

namespace tr {
namespace {

struct Domain {
    TetMesh mesh;
    FaceAdjacency adjacency;
};

Field sample_field(const TetMesh& mesh, Vec3 (*velocity)(const Vec3&)) {
    std::vector<double> v;
    for (const Vec3& p : mesh.points()) {
        const Vec3 u = velocity(p);
        v.insert(v.end(), {u.x, u.y, u.z});
    }
    return make_double_field("v", 3, v);
}

// [lo, lo + size]^3 as a mixed grid of n^3 boxes, with a velocity field v(p).
Domain box_domain(Vec3 (*velocity)(const Vec3&), int n = 8, double lo = -2.0, double size = 4.0) {
    testing::MixedGridOptions o;
    o.nx = o.ny = o.nz = n;
    o.linear = glm::dmat3(size / n);
    o.offset = Vec3(lo);
    Domain d;
    d.mesh = tetrahedralize(testing::make_mixed_grid(o)).value();
    d.adjacency = build_face_adjacency(d.mesh).value();
    EXPECT_TRUE(d.mesh.add_point_field(sample_field(d.mesh, velocity)).ok());
    return d;
}

double longest_front_edge(const FlowFront& front) {
    double longest = 0;
    for (const auto& t : front.triangles) {
        for (int e = 0; e < 3; ++e) {
            longest =
                std::max(longest, glm::distance(front.points[t[e]], front.points[t[(e + 1) % 3]]));
        }
    }
    return longest;
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
    // Div v = 1: a fluid element's volume grows as e^t, so the concentration of a tet of age a
    // is e^-(a - dt/2) relative to the first layer's (age dt/2).
    const Field* age = find_field(fv->mesh.cell_fields(), "age");
    ASSERT_NE(age, nullptr);
    for (CellId t = 0; t < fv->mesh.num_tets(); ++t) {
        const double expected = std::exp(-(age->get(t) - 0.5 * options.dt));
        ASSERT_NEAR(c->get(t), expected, 0.01 * expected) << t;
    }
}

// v = (1, y, -z): divergence-free and linear (so exact on the mesh), stretching the front
// along y by e^t. The dye fills seed area x time, each layer keeps its volume, and adaptive
// subdivision keeps every front edge under the threshold at every layer, where without it the
// front's edges grow past it.
TEST(FlowVolume, AdaptiveSubdivisionKeepsTheFrontResolved) {
    const Domain d = box_domain([](const Vec3& p) { return Vec3(1.0, p.y, -p.z); });
    DyeSeed seed;
    seed.center = Vec3(-1.8, 0.05, 0.1);
    seed.width = seed.height = 0.8;
    seed.resolution = 8;
    seed.normal = Vec3(1, 0, 0);
    FlowVolumeOptions options;
    options.dt = 0.1;
    options.split_threshold = 2.0;
    const double limit = options.split_threshold * seed.spacing();
    for (int steps = 1; steps <= 14; ++steps) {
        options.steps = steps;
        auto fv = grow_flow_volume(d.mesh, d.adjacency, velocity(d), seed, options);
        ASSERT_TRUE(fv.ok()) << fv.error().to_string();
        EXPECT_LE(longest_front_edge(fv->front), limit) << steps;
        EXPECT_EQ(fv->unresolved_edges, 0u);
        EXPECT_EQ(fv->particles_stopped, 0u);
        EXPECT_NEAR(fv->mesh.real_volume(), 0.64 * steps * options.dt, 0.005 * 0.64 * steps * 0.1);
        if (steps == 14) {
            EXPECT_GT(fv->particles_inserted, 50u);  // e^1.4 = 4: many splits
            const double first = layer_volume(*fv, 0);
            for (std::size_t k = 1; k < fv->layer_tets.size(); ++k) {
                EXPECT_NEAR(layer_volume(*fv, k), first, 0.01 * first) << k;
            }
        }
    }
    options.split_threshold = 0;
    auto coarse = grow_flow_volume(d.mesh, d.adjacency, velocity(d), seed, options);
    ASSERT_TRUE(coarse.ok());
    EXPECT_EQ(coarse->particles_inserted, 0u);
    EXPECT_GT(longest_front_edge(coarse->front), 1.5 * limit);
}

// The ABC flow (Arnold-Beltrami-Childress), divergence-free and chaotic, on [0, 2 pi]^3:
// every layer keeps the first one's volume (within 1%: the piecewise-linear field is only
// nearly divergence-free), with the front refined where it stretches.
TEST(FlowVolume, AbcFlowConservesEachLayersVolume) {
    const Domain d = box_domain(
        [](const Vec3& p) {
            const double a = std::sqrt(3.0), b = std::sqrt(2.0), c = 1.0;
            return Vec3(a * std::sin(p.z) + c * std::cos(p.y),
                        b * std::sin(p.x) + a * std::cos(p.z),
                        c * std::sin(p.y) + b * std::cos(p.x));
        },
        24, 0.0, 2 * M_PI);
    DyeSeed seed;
    seed.center = Vec3(3.0, 3.2, 2.9);
    seed.width = seed.height = 0.5;
    seed.resolution = 10;
    FlowVolumeOptions options;
    options.steps = 20;
    options.dt = 0.05;
    auto fv = grow_flow_volume(d.mesh, d.adjacency, velocity(d), seed, options);
    ASSERT_TRUE(fv.ok()) << fv.error().to_string();
    EXPECT_EQ(fv->particles_stopped, 0u);
    const double first = layer_volume(*fv, 0);
    for (std::size_t k = 1; k < fv->layer_tets.size(); ++k) {
        EXPECT_NEAR(layer_volume(*fv, k), first, 0.01 * first) << k;
    }
}

// Unsteady uniform flow, speed 1 at t = 0 rising linearly to 2 at t = 1: the dye released at
// t = 0 fills seed area x the integral of the speed, 1.5; released at t = 0.5 for 0.5, 0.875.
TEST(FlowVolume, UnsteadyFlowIsInterpolatedInTime) {
    const Domain d = box_domain([](const Vec3&) { return Vec3(1, 0, 0); });
    std::vector<Field> samples = {sample_field(d.mesh, [](const Vec3&) { return Vec3(1, 0, 0); }),
                                  sample_field(d.mesh, [](const Vec3&) { return Vec3(2, 0, 0); })};
    const VelocityField field =
        VelocityField::unsteady(d.mesh, std::move(samples), {0.0, 1.0}).value();
    DyeSeed seed;
    seed.center = Vec3(-1.8, 0, 0);
    seed.width = 0.5;
    seed.height = 0.6;
    seed.resolution = 4;
    FlowVolumeOptions options;
    options.steps = 10;
    options.dt = 0.1;
    auto fv = grow_flow_volume(d.mesh, d.adjacency, field, seed, options);
    ASSERT_TRUE(fv.ok()) << fv.error().to_string();
    EXPECT_NEAR(fv->mesh.real_volume(), 0.3 * 1.5, 1e-9);
    options.start_time = 0.5;
    options.steps = 5;
    auto later = grow_flow_volume(d.mesh, d.adjacency, field, seed, options);
    ASSERT_TRUE(later.ok()) << later.error().to_string();
    EXPECT_NEAR(later->mesh.real_volume(), 0.3 * (0.5 * (1.5 + 2.0) * 0.5), 1e-9);
    options.steps = 6;  // runs to t = 1.1, past the last sample
    const auto past = grow_flow_volume(d.mesh, d.adjacency, field, seed, options);
    ASSERT_FALSE(past.ok());
    EXPECT_NE(past.error().message.find("outside the velocity's times"), std::string::npos);
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
    FlowVolumeOptions low_threshold;
    low_threshold.split_threshold = 1.0;
    EXPECT_FALSE(grow_flow_volume(d.mesh, d.adjacency, velocity(d), DyeSeed{}, low_threshold).ok());
    std::vector<double> nan(d.mesh.num_points() * 3, std::nan(""));
    const Field bad_field = make_double_field("v", 3, nan);
    DyeSeed with_normal;
    with_normal.normal = Vec3(1, 0, 0);
    const auto invalid = grow_flow_volume(d.mesh, d.adjacency, bad_field, with_normal);
    EXPECT_FALSE(invalid.ok());  // every particle stops at once: no layer
}

// A straining flow, so the front is refined and layers meet split ones (T-junctions on flat
// faces): still the same picture in any order.
TEST(FlowVolume, RendersTheSameInAnyOrder) {
    const Domain d = box_domain([](const Vec3& p) { return Vec3(1.0, 0.6 * p.y, -0.6 * p.z); });
    DyeSeed seed;
    seed.center = Vec3(-1.6, 0, 0);
    seed.width = seed.height = 1.0;
    seed.resolution = 6;
    FlowVolumeOptions options;
    options.steps = 12;
    options.dt = 0.2;
    auto fv = grow_flow_volume(d.mesh, d.adjacency, velocity(d), seed, options);
    ASSERT_TRUE(fv.ok());
    EXPECT_GT(fv->particles_inserted, 0u);
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
    // The dye is in the picture: pixels differing from the background by more than half an
    // 8-bit level.
    const std::size_t covered =
        compare_images(first, Image(frame.width(), frame.height()), Vec3f(0.0f)).foreground_pixels;
    std::printf("[ flow volume, any order ] %zu of %d pixels covered\n", covered,
                frame.width() * frame.height());
    EXPECT_GT(covered, 700u);  // measured 800 of 6912
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
