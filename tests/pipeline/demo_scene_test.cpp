// The built-in demo scenes (pipeline/demo_scene.h): the plume's grid and temperature, and the
// fused demo drawing two meshes that overlap in space, both seen in one picture.
#include <core/config.h>
#include <mesh/field.h>
#include <pipeline/demo_scene.h>
#include <pipeline/pipeline.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#if TETRENDER_HAS_TETGEN
#include <mesh/copyleft/cylinder_demo.h>
#endif

namespace tr {
namespace {

TEST(DemoPlume, GridLiesBehindTheCylinderInsideTheFlowBox) {
    const UnstructuredMesh grid = make_demo_plume_grid(6000);
    EXPECT_GT(grid.num_cells(), 4500u);
    EXPECT_LT(grid.num_cells(), 7500u);
    for (CellType type : grid.types) EXPECT_EQ(type, CellType::kHexahedron);
    const Field* temperature = find_field(grid.point_fields, "temperature");
    ASSERT_NE(temperature, nullptr);
    for (std::size_t i = 0; i < grid.num_points(); ++i) {
        const Vec3& p = grid.points[i];
        ASSERT_GE(p.x, 0.55 - 1e-12);
        ASSERT_LE(p.x, 4.9 + 1e-12);
        ASSERT_LE(std::abs(p.y), 1.5 + 1e-12);
        ASSERT_LE(std::abs(p.z), 0.95 + 1e-12);
        ASSERT_GE(std::hypot(p.x, p.y), 0.55 - 1e-12);  // outside the cylinder (radius 0.5)
        const double t = temperature->get(i);
        ASSERT_GE(t, 0.0);
        ASSERT_LE(t, 1.0);
        EXPECT_NEAR(t, demo_plume_temperature(p), 1e-6);
    }
}

// The sheet y = 0 at the cylinder's rear, turned by the swirl's angle as it travels at U = 1,
// is at exp(-xi / 3) everywhere; off the sheet it is cooler.
TEST(DemoPlume, TemperatureFollowsTheSheetWoundByTheSwirl) {
    for (double xi : {0.0, 0.5, 1.7, 4.0}) {
        for (double rho : {0.1, 0.4, 0.9}) {
            // The swirl's angular velocity written out: circulation 2, core 0.6.
            const double omega =
                2.0 / (2 * std::numbers::pi * rho) * (1 - std::exp(-rho * rho / 0.36)) / rho;
            const double phi = std::numbers::pi / 2 + omega * xi;
            const Vec3 on(0.5 + xi, rho * std::cos(phi), rho * std::sin(phi));
            EXPECT_NEAR(demo_plume_temperature(on), std::exp(-xi / 3), 1e-12) << xi << " " << rho;
            // A quarter turn off the sheet, rho from it: cooler where rho is 1.3 sigma or more.
            if (rho < 0.4) continue;
            const Vec3 off(0.5 + xi, rho * std::cos(phi + std::numbers::pi / 2),
                           rho * std::sin(phi + std::numbers::pi / 2));
            EXPECT_LT(demo_plume_temperature(off), 0.5 * std::exp(-xi / 3)) << xi << " " << rho;
        }
    }
}

#if TETRENDER_HAS_TETGEN
// The swirl in the test above is the demo flow's: at (x, 0, rho) the potential flow has no y
// component, so the velocity's y component is the swirl's -u_phi.
TEST(DemoPlume, SwirlIsTheFlowsSwirl) {
    for (double rho : {0.1, 0.4, 0.9}) {
        const double u_phi = 2.0 / (2 * std::numbers::pi * rho) * (1 - std::exp(-rho * rho / 0.36));
        EXPECT_NEAR(std::abs(cylinder_demo_velocity(Vec3(2.0, 0.0, rho)).y), u_phi, 1e-9);
    }
}

// The fraction of pixels where a and b differ by more than `levels` 8-bit levels in a channel.
std::vector<bool> differs(const Image& a, const Image& b, double levels) {
    std::vector<bool> out(a.pixels.size());
    for (std::size_t i = 0; i < out.size(); ++i) {
        const Vec3f d = glm::abs(a.pixels[i] - b.pixels[i]);
        out[i] = std::max({d.x, d.y, d.z}) > levels / 255.0;
    }
    return out;
}

double fraction(const std::vector<bool>& mask) {
    return static_cast<double>(std::count(mask.begin(), mask.end(), true)) / mask.size();
}

TEST(DemoScene, FusedDrawsTwoOverlappingVolumesBothSeen) {
    DemoOptions options;
    options.kind = DemoKind::kFused;
    options.tets = 20000;
    options.width = 240;
    options.height = 135;
    auto demo = make_demo_scene(options);
    ASSERT_TRUE(demo.ok()) << demo.error().to_string();
    const Scene& fused = demo->scene;
    ASSERT_EQ(fused.volumes.size(), 2u);
    ASSERT_NE(demo->plume, nullptr);
    EXPECT_GT(demo->plume->num_tets(), 15000u);
    EXPECT_LT(demo->plume->num_tets(), 25000u);
    // The plume's grid lies inside the flow's box: the meshes overlap in space.
    const Bounds3 flow = demo->flow->bounds(), plume = demo->plume->bounds();
    for (int axis = 0; axis < 3; ++axis) {
        EXPECT_LT(flow.lo[axis], plume.lo[axis]);
        EXPECT_GT(flow.hi[axis], plume.hi[axis]);
    }

    Pipeline pipeline;
    auto both = pipeline.render(fused);
    ASSERT_TRUE(both.ok()) << both.error().to_string();
    EXPECT_EQ(both->stats.number("volumes"), 2);
    EXPECT_GT(both->stats.number("overlap_intervals"), 0);
    Scene flow_only = fused, plume_only = fused;
    flow_only.volumes.erase(flow_only.volumes.begin() + 1);
    plume_only.volumes.erase(plume_only.volumes.begin());
    Scene cylinder_only = flow_only;
    cylinder_only.volumes[0].transfer_function =
        TransferFunction::create({{0, Vec3(0.0)}}, {{0, 0.0}}, 1.0).value();
    auto flow_picture = pipeline.render(flow_only);
    auto plume_picture = pipeline.render(plume_only);
    auto cylinder_picture = pipeline.render(cylinder_only);
    ASSERT_TRUE(flow_picture.ok() && plume_picture.ok() && cylinder_picture.ok());
    const Image& fused_image = both->image;

    // Where each volume alone shows (beyond the cylinder and background), and where both do.
    const auto flow_seen = differs(flow_picture->image, cylinder_picture->image, 2);
    const auto plume_seen = differs(plume_picture->image, cylinder_picture->image, 2);
    std::vector<bool> both_seen(flow_seen.size());
    for (std::size_t i = 0; i < both_seen.size(); ++i) both_seen[i] = flow_seen[i] && plume_seen[i];
    // The fused picture differs from each alone where the other one shows.
    const auto not_flow_alone = differs(fused_image, flow_picture->image, 2);
    const auto not_plume_alone = differs(fused_image, plume_picture->image, 2);
    std::vector<bool> neither_alone(both_seen.size());
    for (std::size_t i = 0; i < both_seen.size(); ++i) {
        neither_alone[i] = not_flow_alone[i] && not_plume_alone[i];
    }
    std::printf(
        "fused demo: flow seen on %.3f of the pixels, plume %.3f, both %.3f; the fused picture "
        "differs from the flow alone on %.3f, from the plume alone on %.3f, from both on %.3f\n",
        fraction(flow_seen), fraction(plume_seen), fraction(both_seen), fraction(not_flow_alone),
        fraction(not_plume_alone), fraction(neither_alone));
    // Measured (240 x 135, 20k + 20k tets): flow 0.125, plume 0.066, both 0.057; differs from
    // the flow alone on 0.066, the plume alone on 0.124, both on 0.055. Bounds: 0.8 x measured.
    EXPECT_GT(fraction(flow_seen), 0.10);
    EXPECT_GT(fraction(plume_seen), 0.053);
    EXPECT_GT(fraction(both_seen), 0.045);
    EXPECT_GT(fraction(not_flow_alone), 0.053);
    EXPECT_GT(fraction(not_plume_alone), 0.10);
    EXPECT_GT(fraction(neither_alone), 0.044);
}
#endif

}  // namespace
}  // namespace tr
