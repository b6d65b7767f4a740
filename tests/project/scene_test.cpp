// Scene files as ../shared/spec/scene.md fixes them, and the transfer function.
#include <project/scene.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>

namespace tr {
namespace {

const char* kScene = R"({
  "mesh": "data/blunt_fin.vtu",
  "scalar": "density",
  "component": 1,
  "transfer_function": {
    "color":   [[0, 0, 0, 1], [1, 1, 0.5, 0]],
    "opacity": [[0, 0], [0.5, 0.5], [1, 0.9]],
    "unit_distance": 2.0
  },
  "camera": {
    "position": [0, 0, 10], "focal_point": [0, 0, 0], "view_up": [0, 1, 0],
    "view_angle": 40, "parallel": true, "parallel_scale": 3
  },
  "image": { "width": 320, "height": 200, "background": [0.1, 0.2, 0.3] },
  "time_step": 2
})";

Result<Scene> parse(const std::string& text) { return parse_scene(text, "/base", "s.json"); }

std::string replace(std::string text, const std::string& from, const std::string& to) {
    const auto pos = text.find(from);
    EXPECT_NE(pos, std::string::npos) << from;
    return text.replace(pos, from.size(), to);
}

TEST(Scene, ParsesEveryKey) {
    auto scene = parse(kScene);
    ASSERT_TRUE(scene.ok()) << scene.error().to_string();
    EXPECT_EQ(scene->mesh, std::filesystem::path("/base/data/blunt_fin.vtu"));
    EXPECT_EQ(scene->scalar, "density");
    EXPECT_EQ(scene->component, 1);
    EXPECT_EQ(scene->width, 320);
    EXPECT_EQ(scene->height, 200);
    EXPECT_EQ(scene->time_step, 2);
    EXPECT_TRUE(scene->camera.parallel);
    EXPECT_DOUBLE_EQ(scene->camera.parallel_scale, 3);
    EXPECT_DOUBLE_EQ(scene->camera.view_angle, 40);
    EXPECT_DOUBLE_EQ(scene->background.z, 0.3);
    EXPECT_DOUBLE_EQ(scene->transfer_function.unit_distance(), 2.0);
}

TEST(Scene, DefaultsAsTheSpecSays) {
    std::string text = replace(kScene, R"("component": 1,)", "");
    text = replace(text, ",\n  \"time_step\": 2", "");
    text = replace(text, R"(,
    "view_angle": 40, "parallel": true, "parallel_scale": 3)",
                   "");
    text = replace(text, R"(, "background": [0.1, 0.2, 0.3])", "");
    auto scene = parse(text);
    ASSERT_TRUE(scene.ok()) << scene.error().to_string();
    EXPECT_EQ(scene->component, -1);
    EXPECT_EQ(scene->time_step, 0);
    EXPECT_FALSE(scene->camera.parallel);
    EXPECT_DOUBLE_EQ(scene->camera.view_angle, 30);
    EXPECT_DOUBLE_EQ(scene->camera.parallel_scale, 1);
    EXPECT_EQ(scene->background, Vec3(0.0));
}

TEST(SceneBadInput, ErrorsNameTheJsonPath) {
    struct Case {
        std::string from, to, path;
    };
    const Case cases[] = {
        {R"("time_step": 2)", R"("time_step": 2, "colour": 1)", "$.colour: unknown key"},
        {R"("view_angle": 40)", R"("view_angle": 40, "fov": 3)", "$.camera.fov: unknown key"},
        {R"("position": [0, 0, 10])", R"("position": [0, 0])", "$.camera.position: expected"},
        {R"("position": [0, 0, 10])", R"("position": [0, "a", 10])", "$.camera.position[1]"},
        {R"("width": 320)", R"("width": 0)", "$.image.width: must be between"},
        {R"("width": 320)", R"("width": 100000)", "$.image.width"},
        {R"("width": 320)", R"("width": 3.5)", "$.image.width: expected an integer"},
        {R"("scalar": "density",)", "", "$.scalar: missing"},
        {R"("parallel": true)", R"("parallel": 1)", "$.camera.parallel"},
        {R"([0.5, 0.5])", R"([0.5, 1.0])", "opacity point 1"},
        {R"([0.5, 0.5])", R"([-0.5, 0.5])", "opacity point 1: scalars must not decrease"},
        {R"("unit_distance": 2.0)", R"("unit_distance": 0)", "unit_distance"},
        {R"("view_up": [0, 1, 0])", R"("view_up": [0, 0, 1])", "$.camera.view_up"},
        {R"("focal_point": [0, 0, 0])", R"("focal_point": [0, 0, 10])", "focal_point"},
        {R"("component": 1)", R"("component": "x")", "$.component"},
        {R"("time_step": 2)", R"("time_step": -1)", "$.time_step"},
        {R"("view_angle": 40)", R"("view_angle": 180)", "$.camera.view_angle"},
        {R"("background": [0.1, 0.2, 0.3])", R"("background": [0.1, 0.2, 3])", "background"},
    };
    for (const Case& c : cases) {
        auto scene = parse(replace(kScene, c.from, c.to));
        ASSERT_FALSE(scene.ok()) << c.to;
        const std::string line = scene.error().to_string();
        EXPECT_NE(line.find(c.path), std::string::npos) << line;
        EXPECT_EQ(line.find('\n'), std::string::npos);
        EXPECT_EQ(line.rfind("s.json: error: ", 0), 0u) << line;
    }
}

TEST(SceneBadInput, MalformedJsonSaysWhere) {
    auto scene = parse("{\n  \"mesh\": \"a.vtu\",\n  oops\n}");
    ASSERT_FALSE(scene.ok());
    EXPECT_NE(scene.error().message.find("line 3"), std::string::npos) << scene.error().message;
    EXPECT_FALSE(parse("").ok());
    EXPECT_FALSE(parse("[1, 2]").ok());
    EXPECT_FALSE(read_scene("/no/such/scene.json").ok());
}

TEST(Scene, OpaqueSurfacesExtension) {
    std::string text = replace(kScene, ",\n  \"time_step\": 2",
                               R"(, "opaque": [{"file": "body.stl", "color": [1, 0, 0]},
                                               {"side_set": "*"}, {"boundary": true}])");
    auto scene = parse(text);
    ASSERT_TRUE(scene.ok()) << scene.error().to_string();
    ASSERT_EQ(scene->opaque.size(), 3u);
    EXPECT_TRUE(scene->opaque[2].boundary);
    EXPECT_EQ(scene->opaque[0].file, std::filesystem::path("/base/body.stl"));
    EXPECT_EQ(scene->opaque[0].color, Vec3(1, 0, 0));
    EXPECT_EQ(scene->opaque[1].side_set, "*");
    EXPECT_EQ(scene->opaque[1].color, Vec3(0.8));
    auto both = parse(replace(kScene, ",\n  \"time_step\": 2",
                              R"(, "opaque": [{"file": "a.stl", "side_set": "x"}])"));
    ASSERT_FALSE(both.ok());
    EXPECT_NE(both.error().message.find("$.opaque[0]"), std::string::npos);
}

TEST(Scene, FlowVolumeExtension) {
    const std::string key = R"(, "flow_volume": {"vectors": "V", "seed_center": [1, 2, 3],
        "seed_size": [0.5, 0.25], "seed_resolution": 8, "seed_normal": [0, 0, 1], "steps": 7,
        "dt": 0.2, "compressible": true, "split_threshold": 3, "unsteady": true,
        "start_time": 0.5, "color": [1, 0.5, 0], "opacity": 0.4, "unit_distance": 0.1,
        "context": true})";
    auto scene = parse(replace(kScene, ",\n  \"time_step\": 2", key));
    ASSERT_TRUE(scene.ok()) << scene.error().to_string();
    ASSERT_TRUE(scene->flow_volume.has_value());
    const FlowVolumeSpec& f = *scene->flow_volume;
    EXPECT_EQ(f.vectors, "V");
    EXPECT_EQ(f.seed_center, Vec3(1, 2, 3));
    EXPECT_EQ(f.seed_height, 0.25);
    EXPECT_EQ(f.seed_resolution, 8);
    EXPECT_EQ(f.seed_normal, Vec3(0, 0, 1));
    EXPECT_EQ(f.steps, 7);
    EXPECT_TRUE(f.compressible && f.unsteady && f.context);
    EXPECT_EQ(f.split_threshold, 3.0);
    EXPECT_EQ(f.start_time, 0.5);
    EXPECT_EQ(f.unit_distance, 0.1);
    // Written and read back: the same values.
    const auto dir = std::filesystem::temp_directory_path() / "tetrender_scene_fv_test";
    std::filesystem::create_directories(dir);
    ASSERT_TRUE(write_scene(*scene, dir / "fv.json").ok());
    auto back = read_scene(dir / "fv.json");
    std::filesystem::remove_all(dir);
    ASSERT_TRUE(back.ok()) << back.error().to_string();
    ASSERT_TRUE(back->flow_volume.has_value());
    EXPECT_EQ(back->flow_volume->seed_normal, f.seed_normal);
    EXPECT_EQ(back->flow_volume->start_time, f.start_time);
    EXPECT_EQ(back->flow_volume->color, f.color);
    EXPECT_EQ(back->flow_volume->dt, f.dt);
    for (const auto& [bad, where] : std::vector<std::pair<std::string, std::string>>{
             {R"(, "flow_volume": {"seed_center": [0, 0, 0], "seed_size": [1, 1]})",
              "$.flow_volume.vectors"},
             {R"(, "flow_volume": {"vectors": "V", "seed_center": [0, 0, 0], "seed_size": [1, 0]})",
              "$.flow_volume.seed_size"},
             {R"(, "flow_volume": {"vectors": "V", "seed_center": [0, 0, 0], "seed_size": [1, 1],
                 "split_threshold": 1})",
              "$.flow_volume.split_threshold"},
             {R"(, "flow_volume": {"vectors": "V", "seed_center": [0, 0, 0], "seed_size": [1, 1],
                 "opacity": 1})",
              "$.flow_volume.opacity"}}) {
        auto rejected = parse(replace(kScene, ",\n  \"time_step\": 2", bad));
        ASSERT_FALSE(rejected.ok()) << bad;
        EXPECT_NE(rejected.error().message.find(where), std::string::npos)
            << rejected.error().message;
    }
}

TEST(Scene, WriteThenReadGivesTheSameScene) {
    auto scene = parse(kScene);
    ASSERT_TRUE(scene.ok());
    const auto dir = std::filesystem::temp_directory_path() / "tetrender_scene_test";
    std::filesystem::create_directories(dir);
    scene->mesh = dir / "meshes" / "m.vtu";
    const auto path = dir / "out.scene.json";
    ASSERT_TRUE(write_scene(*scene, path).ok());
    auto back = read_scene(path);
    ASSERT_TRUE(back.ok()) << back.error().to_string();
    EXPECT_EQ(std::filesystem::weakly_canonical(back->mesh),
              std::filesystem::weakly_canonical(scene->mesh));
    EXPECT_EQ(back->component, 1);
    EXPECT_EQ(back->camera.position, scene->camera.position);
    EXPECT_EQ(back->transfer_function.opacity_points().size(), 3u);
    std::filesystem::remove_all(dir);
}

TEST(Scene, ReadsTheVtkHarnessExamples) {
    const std::filesystem::path examples =
        std::filesystem::path(TETRENDER_SHARED_DATA_DIR) / ".." / "tools" / "vtk" / "examples";
    if (!std::filesystem::is_directory(examples)) {
        const char* ci = std::getenv("CI");
        if (ci && std::string(ci) == "true") FAIL() << "missing " << examples;
        GTEST_SKIP() << "no " << examples;
    }
    int n = 0;
    for (const auto& entry : std::filesystem::directory_iterator(examples)) {
        if (entry.path().string().find(".scene.json") == std::string::npos) continue;
        auto scene = read_scene(entry.path());
        EXPECT_TRUE(scene.ok()) << scene.error().to_string();
        ++n;
    }
    EXPECT_GE(n, 4);
}

TEST(TransferFunction, PiecewiseLinearClampedAndExtinctionAsSpecified) {
    auto tf = TransferFunction::create({{0, {0, 0, 1}}, {2, {1, 0, 0}}},
                                       {{0, 0.0}, {1, 0.5}, {3, 0.9}}, 2.0);
    ASSERT_TRUE(tf.ok());
    EXPECT_EQ(tf->color(-5), Vec3(0, 0, 1));
    EXPECT_EQ(tf->color(7), Vec3(1, 0, 0));
    EXPECT_NEAR(tf->color(0.5).r, 0.25, 1e-15);
    EXPECT_NEAR(tf->opacity(0.5), 0.25, 1e-15);
    EXPECT_NEAR(tf->opacity(2), 0.7, 1e-15);
    EXPECT_NEAR(tf->opacity(10), 0.9, 1e-15);
    // A slab of unit_distance at constant s has opacity a(s).
    const double kappa = tf->extinction(1.0);
    EXPECT_NEAR(1 - std::exp(-kappa * 2.0), 0.5, 1e-15);
    EXPECT_DOUBLE_EQ(tf->extinction(0.0), 0.0);
}

}  // namespace
}  // namespace tr
