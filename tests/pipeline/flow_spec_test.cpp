// What `tetrender flowvol` chooses from the flow when the seed or dt is not given
// (pipeline/flow_volume_scene.h choose_flow_spec), and the camera turned to a small dye.
#include <pipeline/flow_volume_scene.h>
#include <pipeline/pipeline.h>
#include <tests/support/freudenthal_box.h>

#include <gtest/gtest.h>

#include <cmath>

namespace tr {
namespace {

// The cube [0, 4]^3 of unit boxes, with the flow v = (1 + x, 0, 0): fastest (5) on x = 4.
std::shared_ptr<const TetMesh> shear_box() {
    TetMesh mesh = testing::freudenthal_box(4, 4, 4, Vec3(0.0), Vec3(4.0));
    std::vector<float> v;
    for (const Vec3& p : mesh.points()) v.insert(v.end(), {static_cast<float>(1 + p.x), 0, 0});
    EXPECT_TRUE(mesh.add_point_field(make_float_field("v", 3, v)).ok());
    return std::make_shared<const TetMesh>(std::move(mesh));
}

TEST(ChooseFlowSpec, SeedWhereTheFlowIsFastestAndDtFromItsSpeed) {
    Pipeline pipeline;
    SceneVolume volume;
    volume.mesh = "shear";
    volume.tets = shear_box();
    const FlowDomain domain = pipeline.flow_domain(volume).value();
    FlowVolumeSpec spec;
    spec.vectors = "v";
    spec.steps = 20;
    std::vector<std::string> notes;
    const FlowVolumeSpec chosen =
        choose_flow_spec(domain, spec, {.seed_center = true, .seed_size = true, .dt = true}, &notes)
            .value();
    // The centroid of a tet at a point on x = 4: x in (3, 4), inside the cube.
    EXPECT_GT(chosen.seed_center.x, 3.0);
    EXPECT_LT(chosen.seed_center.x, 4.0);
    const double diagonal = 4 * std::sqrt(3.0);
    EXPECT_DOUBLE_EQ(chosen.seed_width, diagonal / 8);
    EXPECT_DOUBLE_EQ(chosen.seed_height, diagonal / 8);
    EXPECT_NEAR(chosen.dt, kDyeTravel * diagonal / (20 * 5.0), 1e-6);
    ASSERT_EQ(notes.size(), 3u);
    EXPECT_NE(notes[0].find("where the flow is fastest (speed 5)"), std::string::npos) << notes[0];
    // A centre given: dt from the speed at the point nearest it (x = 1: speed 2); nothing said
    // of what was given.
    notes.clear();
    spec.seed_center = Vec3(1.1, 2, 2);
    const FlowVolumeSpec given = choose_flow_spec(domain, spec, {.dt = true}, &notes).value();
    EXPECT_EQ(given.seed_center, spec.seed_center);
    EXPECT_EQ(given.seed_width, spec.seed_width);
    EXPECT_NEAR(given.dt, kDyeTravel * diagonal / (20 * 2.0), 1e-6);
    ASSERT_EQ(notes.size(), 1u);
    EXPECT_NE(notes[0].find("no --dt: dt = "), std::string::npos) << notes[0];
}

TEST(ChooseFlowSpec, AStillFlowAndAnUnknownArrayAreErrors) {
    Pipeline pipeline;
    SceneVolume volume;
    volume.mesh = "still";
    TetMesh mesh = testing::freudenthal_box(4, 4, 4, Vec3(0.0), Vec3(4.0));
    ASSERT_TRUE(mesh.add_point_field(
                        make_float_field("v", 3, std::vector<float>(3 * mesh.num_points(), 0.0f)))
                    .ok());
    volume.tets = std::make_shared<const TetMesh>(std::move(mesh));
    const FlowDomain domain = pipeline.flow_domain(volume).value();
    FlowVolumeSpec spec;
    spec.vectors = "v";
    const auto still = choose_flow_spec(domain, spec, {.dt = true});
    ASSERT_FALSE(still.ok());
    EXPECT_NE(still.error().message.find("is zero everywhere"), std::string::npos);
    spec.vectors = "w";
    EXPECT_EQ(choose_flow_spec(domain, spec, {.dt = true}).error().code, ErrorCode::kNotFound);
}

// A dye in a corner of the picture is framed alone; one that fills it is left as it is.
TEST(DyeCamera, FramesASmallDyeAndLeavesALargeOne) {
    const TetMesh box = testing::freudenthal_box(4, 4, 4, Vec3(0.0), Vec3(4.0));  // [0, 4]^3
    Camera far;
    far.position = Vec3(2, -60, 2);
    far.focal_point = Vec3(2, 2, 2);
    far.view_up = Vec3(0, 0, 1);
    const auto framed = dye_camera(box, far, 200, 150);
    ASSERT_TRUE(framed.has_value());
    // From the same direction, every corner inside the picture and the box wider than half of
    // it.
    const Vec3 was = glm::normalize(far.position - far.focal_point);
    const Vec3 now = glm::normalize(framed->position - framed->focal_point);
    EXPECT_NEAR(glm::dot(was, now), 1.0, 1e-9);
    const CameraFrame frame(*framed, 200, 150);
    double lo = 1e9, hi = -1e9;
    for (const Vec3& p : box.points()) {
        const Vec3 image = frame.project(p);
        EXPECT_GE(image.x, 0.0);
        EXPECT_LE(image.x, 200.0);
        EXPECT_GE(image.y, 0.0);
        EXPECT_LE(image.y, 150.0);
        lo = std::min(lo, image.x), hi = std::max(hi, image.x);
    }
    EXPECT_GT(hi - lo, 100.0);
    // Near: already large in the picture.
    Camera near = far;
    near.position = Vec3(2, -8, 2);
    EXPECT_FALSE(dye_camera(box, near, 200, 150).has_value());
}

}  // namespace
}  // namespace tr
