// Scene files as ../shared/spec/scene.md fixes them, and the transfer function.
#include <pipeline/scene.h>
#include <project/colormap.h>
#include <tests/support/temp_dir.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <stdlib.h>

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
    ASSERT_EQ(scene->volumes.size(), 1u);
    EXPECT_FALSE(scene->volumes_key);
    const SceneVolume& v = scene->volumes[0];
    EXPECT_EQ(v.mesh, std::filesystem::path("/base/data/blunt_fin.vtu"));
    EXPECT_EQ(v.scalar, "density");
    EXPECT_EQ(v.component, 1);
    EXPECT_EQ(v.time_step, 2);
    EXPECT_EQ(scene->width, 320);
    EXPECT_EQ(scene->height, 200);
    EXPECT_EQ(scene->method_name(), "projected-tetrahedra");
    EXPECT_EQ(scene->source, "s.json");
    EXPECT_TRUE(scene->camera.parallel);
    EXPECT_DOUBLE_EQ(scene->camera.parallel_scale, 3);
    EXPECT_DOUBLE_EQ(scene->camera.view_angle, 40);
    EXPECT_DOUBLE_EQ(scene->background.z, 0.3);
    EXPECT_DOUBLE_EQ(v.transfer_function.unit_distance(), 2.0);
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
    EXPECT_EQ(scene->volumes[0].component, -1);
    EXPECT_EQ(scene->volumes[0].time_step, 0);
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
    const testing::TempDir temp("tetrender_scene_");
    const std::filesystem::path& dir = temp.path();
    ASSERT_TRUE(write_scene(*scene, dir / "fv.json").ok());
    auto back = read_scene(dir / "fv.json");
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
    const testing::TempDir temp("tetrender_scene_");
    const std::filesystem::path& dir = temp.path();
    scene->volumes[0].mesh = dir / "meshes" / "m.vtu";
    const auto path = dir / "out.scene.json";
    ASSERT_TRUE(write_scene(*scene, path).ok());
    auto back = read_scene(path);
    ASSERT_TRUE(back.ok()) << back.error().to_string();
    EXPECT_EQ(std::filesystem::weakly_canonical(back->volumes[0].mesh),
              std::filesystem::weakly_canonical(scene->volumes[0].mesh));
    EXPECT_EQ(back->volumes[0].component, 1);
    EXPECT_EQ(back->volumes[0].time_step, 2);
    EXPECT_EQ(back->camera.position, scene->camera.position);
    EXPECT_EQ(back->volumes[0].transfer_function.opacity_points().size(), 3u);
    EXPECT_FALSE(back->method.has_value());
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

// Two volumes, each with its own keys (spec: "Several volumes in one space").
const char* kVolumes = R"({
  "volumes": [
    { "mesh": "fluid.vtu", "scalar": "vorticity",
      "transfer_function": { "color": [[0, 1, 0, 0]], "opacity": [[0, 0.2]], "unit_distance": 1 } },
    { "mesh": "solid.exo", "scalar": "stress", "component": 0, "time_step": 3,
      "transfer_function": { "color": [[0, 0, 0, 1]], "opacity": [[0, 0.4]], "unit_distance": 2 } }
  ],
  "camera": { "position": [0, 0, 10], "focal_point": [0, 0, 0], "view_up": [0, 1, 0] },
  "image": { "width": 64, "height": 48 },
  "method": { "name": "pbvr-image", "repetitions": 64, "seed": 7, "depth": "entry" }
})";

TEST(Scene, VolumesAndMethod) {
    auto scene = parse(kVolumes);
    ASSERT_TRUE(scene.ok()) << scene.error().to_string();
    ASSERT_EQ(scene->volumes.size(), 2u);
    EXPECT_TRUE(scene->volumes_key);
    EXPECT_EQ(scene->volumes[0].mesh, std::filesystem::path("/base/fluid.vtu"));
    EXPECT_EQ(scene->volumes[0].component, -1);
    EXPECT_EQ(scene->volumes[1].scalar, "stress");
    EXPECT_EQ(scene->volumes[1].component, 0);
    EXPECT_EQ(scene->volumes[1].time_step, 3);
    EXPECT_DOUBLE_EQ(scene->volumes[1].transfer_function.unit_distance(), 2.0);
    ASSERT_TRUE(scene->method.has_value());
    EXPECT_EQ(scene->method_name(), "pbvr-image");
    EXPECT_EQ(scene->method->repetitions, 64);
    EXPECT_EQ(scene->method->seed, 7);
    ASSERT_EQ(scene->method->options.size(), 1u);
    EXPECT_EQ(std::get<std::string>(scene->method->options.at("depth")), "entry");
    // Written and read back: the same volumes and method.
    const testing::TempDir temp("tetrender_scene_");
    const std::filesystem::path& dir = temp.path();
    ASSERT_TRUE(write_scene(*scene, dir / "v.json").ok());
    auto back = read_scene(dir / "v.json");
    ASSERT_TRUE(back.ok()) << back.error().to_string();
    ASSERT_EQ(back->volumes.size(), 2u);
    EXPECT_EQ(back->volumes[1].time_step, 3);
    EXPECT_EQ(back->volumes[1].component, 0);
    EXPECT_EQ(back->volumes[0].mesh.filename(), "fluid.vtu");
    ASSERT_TRUE(back->method.has_value());
    EXPECT_EQ(back->method->name, "pbvr-image");
    EXPECT_EQ(back->method->repetitions, 64);
    EXPECT_EQ(back->method->seed, 7);
    EXPECT_EQ(std::get<std::string>(back->method->options.at("depth")), "entry");
}

TEST(Scene, OneVolumeInTheListReadsAsTheTopLevelKeys) {
    auto top = parse(kScene);
    auto listed = parse(R"({"volumes": [{"mesh": "data/blunt_fin.vtu", "scalar": "density",
        "component": 1, "time_step": 2, "transfer_function": {
        "color": [[0, 0, 0, 1], [1, 1, 0.5, 0]], "opacity": [[0, 0], [0.5, 0.5], [1, 0.9]],
        "unit_distance": 2.0}}],
        "camera": {"position": [0, 0, 10], "focal_point": [0, 0, 0], "view_up": [0, 1, 0],
                   "view_angle": 40, "parallel": true, "parallel_scale": 3},
        "image": {"width": 320, "height": 200, "background": [0.1, 0.2, 0.3]}})");
    ASSERT_TRUE(top.ok() && listed.ok()) << listed.error().to_string();
    const SceneVolume& a = top->volumes[0];
    const SceneVolume& b = listed->volumes[0];
    EXPECT_EQ(a.mesh, b.mesh);
    EXPECT_EQ(a.scalar, b.scalar);
    EXPECT_EQ(a.component, b.component);
    EXPECT_EQ(a.time_step, b.time_step);
    EXPECT_EQ(a.transfer_function.opacity_points().size(),
              b.transfer_function.opacity_points().size());
}

TEST(SceneBadInput, VolumesAndMethodErrorsNameTheJsonPath) {
    const std::string both =
        replace(kScene, R"("time_step": 2)", R"("time_step": 2, "volumes": [])");
    std::string seventeen = R"({"volumes": [)";
    for (int i = 0; i < 17; ++i) {
        seventeen +=
            std::string(i ? "," : "") +
            R"({"mesh": "m.vtu", "scalar": "s", "transfer_function": {"color": [[0, 1, 1, 1]],
                     "opacity": [[0, 0.5]], "unit_distance": 1}})";
    }
    seventeen += R"(], "camera": {"position": [0, 0, 1], "focal_point": [0, 0, 0],
                    "view_up": [0, 1, 0]}, "image": {"width": 8, "height": 8}})";
    const std::pair<std::string, std::string> cases[] = {
        {both, "$.volumes: a scene has either"},
        {replace(kVolumes, R"("volumes": [)", R"("volumes": [], "x": [)"), "$.x: unknown key"},
        {replace(kVolumes, R"("time_step": 3)", R"("time_step": 3, "colour": 1)"),
         "$.volumes[1].colour: unknown key"},
        {replace(kVolumes, R"("scalar": "stress",)", ""), "$.volumes[1].scalar: missing"},
        {replace(kVolumes, R"("component": 0)", R"("component": -2)"),
         "$.volumes[1].component: must be >= 0"},
        {seventeen, "$.volumes: expected an array of 1 to 16 volumes"},
        {replace(kVolumes, R"("repetitions": 64)", R"("repetitions": 0)"),
         "$.method.repetitions: must be >= 1"},
        {replace(kVolumes, R"("repetitions": 64)", R"("repetitions": 6.5)"),
         "$.method.repetitions: expected an integer"},
        {replace(kVolumes, R"("seed": 7)", R"("seed": "seven")"),
         "$.method.seed: expected an integer"},
        {replace(kVolumes, R"("name": "pbvr-image", )", ""), "$.method.name: missing"},
        {replace(kVolumes, R"("depth": "entry")", R"("depth": [1])"), "$.method.depth: expected"},
        {replace(kVolumes, R"(, "seed": 7, "depth": "entry" })",
                 R"(}, "opaque": [{"boundary": true, "volume": 2}])"),
         "$.opaque[0].volume: no volume 2"},
    };
    for (const auto& [text, where] : cases) {
        auto scene = parse(text);
        ASSERT_FALSE(scene.ok()) << text;
        const std::string line = scene.error().to_string();
        EXPECT_NE(line.find(where), std::string::npos) << line;
        EXPECT_EQ(line.rfind("s.json: error: ", 0), 0u) << line;
    }
    auto empty = parse(R"({"volumes": [], "camera": {"position": [0, 0, 1],
        "focal_point": [0, 0, 0], "view_up": [0, 1, 0]}, "image": {"width": 8, "height": 8}})");
    ASSERT_FALSE(empty.ok());
    EXPECT_NE(empty.error().message.find("$.volumes: expected an array of 1 to 16"),
              std::string::npos);
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

TEST(TransferFunction, LogScaledFollowsTheLogMapBetweenItsSamples) {
    // Viridis over 7 decades of log10 with a kinked opacity: the log-scaled function of the
    // scalar itself must give, at 10^x, what the original gives at x.
    const TransferFunction over_log =
        TransferFunction::create(
            make_quick_transfer_function("viridis", -4, 3, 0.5, 1.0).value().color_points(),
            {{-4, 0.1}, {-1, 0.6}, {3, 0.3}}, 2.0)
            .value();
    const TransferFunction tf = log_scaled(over_log).value();
    EXPECT_EQ(tf.unit_distance(), 2.0);
    EXPECT_DOUBLE_EQ(tf.color_points().front().s, 1e-4);
    EXPECT_DOUBLE_EQ(tf.color_points().back().s, 1e3);
    double worst_color = 0, worst_opacity = 0;
    std::mt19937 random(7);
    std::uniform_real_distribution<double> x_of(-4.0, 3.0);
    for (int i = 0; i < 20000; ++i) {
        const double x = x_of(random), s = std::pow(10.0, x);
        const Vec3 d = tf.color(s) - over_log.color(x);
        worst_color = std::max({worst_color, std::abs(d.r), std::abs(d.g), std::abs(d.b)});
        worst_opacity = std::max(worst_opacity, std::abs(tf.opacity(s) - over_log.opacity(x)));
    }
    std::printf("log_scaled: worst colour %.2e, worst opacity %.2e\n", worst_color, worst_opacity);
    // Measured 3.2e-4 and 1.4e-4 (a twelfth and a 27th of an 8-bit level; 129 samples over 7
    // decades); asserted with half again as margin.
    EXPECT_LT(worst_color, 5e-4) << worst_color;
    EXPECT_LT(worst_opacity, 2.2e-4) << worst_opacity;
    EXPECT_GT(worst_color, 0.0);  // the samples are not the original's points: linear between
    // The kink of the opacity is a control point: exact there.
    EXPECT_NEAR(tf.opacity(0.1), 0.6, 1e-12);
    // Below the range (zero and negative values included) the low end, above it the high end.
    EXPECT_EQ(tf.color(0.0), over_log.color(-4));
    EXPECT_EQ(tf.color(-5.0), over_log.color(-4));
    EXPECT_EQ(tf.opacity(1e9), over_log.opacity(3));
    EXPECT_FALSE(log_scaled(over_log, 1).ok());
    const TransferFunction huge =
        TransferFunction::create({{0, Vec3(1)}, {400, Vec3(0)}}, {{0, 0.5}}, 1.0).value();
    EXPECT_FALSE(log_scaled(huge).ok());
}

}  // namespace
}  // namespace tr
