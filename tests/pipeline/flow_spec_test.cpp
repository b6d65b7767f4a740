// What `tetrender flowvol` chooses from the flow when the seed or dt is not given
// (pipeline/flow_volume_scene.h choose_flow_spec), and the camera turned to a small dye.
#include <pipeline/flow_volume_scene.h>
#include <pipeline/pipeline.h>
#include <tests/support/freudenthal_box.h>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

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
    EXPECT_NE(notes[0].find("dt chosen: dt = "), std::string::npos) << notes[0];
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
// A scene's flow_volume may leave seed_center, seed_size and dt out: they parse as left to the
// data, a saved scene leaves them out again, and the render chooses them as flowvol does (the
// picture the explicitly chosen spec gives, bit for bit) and says so.
TEST(ResolveFlowSpec, ASceneLeavesTheSeedAndDtToTheFlow) {
    const std::string text = R"({"mesh": "shear.vtu", "scalar": "v",
        "transfer_function": {"color": [[0, 1, 1, 1], [1, 1, 1, 1]],
                              "opacity": [[0, 0.1], [1, 0.1]], "unit_distance": 1},
        "camera": {"position": [12, -10, 9], "focal_point": [2, 2, 2], "view_up": [0, 0, 1]},
        "image": {"width": 64, "height": 48},
        "flow_volume": {"vectors": "v", "steps": 10, "seed_resolution": 4}})";
    Scene scene = parse_scene(text, "/tmp", "chosen.scene.json").value();
    ASSERT_TRUE(scene.flow_volume.has_value());
    const FlowSpecChoices& choose = scene.flow_volume->choose;
    EXPECT_TRUE(choose.seed_center && choose.seed_size && choose.dt);
    const std::string with_seed = R"("flow_volume": {"vectors": "v", "seed_center": [1, 2, 2],)";
    std::string given_text = text;
    given_text.replace(given_text.find(R"("flow_volume": {"vectors": "v",)"),
                       std::string(R"("flow_volume": {"vectors": "v",)").size(), with_seed);
    const Scene given = parse_scene(given_text, "/tmp", "given.scene.json").value();
    EXPECT_FALSE(given.flow_volume->choose.seed_center);
    EXPECT_TRUE(given.flow_volume->choose.seed_size);
    EXPECT_EQ(given.flow_volume->seed_center, Vec3(1, 2, 2));

    // Saved, the scene still leaves them to the flow.
    const std::filesystem::path saved =
        std::filesystem::temp_directory_path() / "tetrender_resolve_flow_spec.scene.json";
    ASSERT_TRUE(write_scene(scene, saved).ok());
    const Scene reread = read_scene(saved).value();
    std::filesystem::remove(saved);
    EXPECT_TRUE(reread.flow_volume->choose.seed_center && reread.flow_volume->choose.seed_size &&
                reread.flow_volume->choose.dt);

    scene.volumes[0].tets = shear_box();
    Pipeline pipeline;
    const RenderResult chosen = pipeline.render(scene).value();
    int said = 0;
    for (const std::string& note : chosen.notes) {
        said += note.find("chosen: ") != std::string::npos ? 1 : 0;
    }
    EXPECT_EQ(said, 3);
    Scene explicit_scene = scene;
    const FlowDomain domain = pipeline.flow_domain(scene.volumes[0]).value();
    explicit_scene.flow_volume =
        choose_flow_spec(domain, *scene.flow_volume, scene.flow_volume->choose).value();
    explicit_scene.flow_volume->choose = {};
    const RenderResult expected = Pipeline().render(explicit_scene).value();
    EXPECT_TRUE(chosen.image.pixels == expected.image.pixels);
    EXPECT_GT(chosen.flow_volume->mesh.num_tets(), 0u);
}

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
