// Bad keys of the scene methods texture-advection and spot-noise: one-line errors naming the
// scene file and the key's JSON path, from check() (kinds, ranges) and from loading (a slice
// that misses the mesh, an iso outside the scalar's range, an unknown vector array).
#include <core/memory_budget.h>
#include <pipeline/pipeline.h>
#include <tests/flowtex/scene_fixtures.h>

#include <gtest/gtest.h>

namespace tr {
namespace {

using testing::advection_method;
using testing::flow_scene;
using testing::top_camera;

// Bad keys: one line, the scene file and the JSON path of the key.
TEST(FlowtexSceneBadInput, KeysOfTheWrongKindOrRange) {
    struct Case {
        const char* method;
        const char* key;
        MethodOption value;
        const char* says;
    };
    const std::vector<Case> cases = {
        {"texture-advection", "slices", std::string("z"), "$.method.slices: expected a list"},
        {"texture-advection", "slices", NumberLists{{0, 0, 0, 0, 0}},
         "$.method.slices[0]: expected 6"},
        {"texture-advection", "slices", NumberLists{{0, 0, 0, 0, 0, 0}},
         "$.method.slices[0]: the normal is zero"},
        {"texture-advection", "sheet_opacity", 1.5,
         "$.method.sheet_opacity: expected a number in (0, 1]"},
        {"texture-advection", "steps", 2.5, "$.method.steps: expected an integer"},
        {"texture-advection", "frame", std::int64_t{200},
         "$.method.frame: frame 200 is past steps (100)"},
        {"texture-advection", "advection", std::string("sideways"), "$.method.advection: expected"},
        {"texture-advection", "reinject", std::int64_t{3}, "$.method.reinject: expected an even"},
        {"texture-advection", "unsteady", std::int64_t{1},
         "$.method.unsteady: expected true or false"},
        {"texture-advection", "colour", std::int64_t{1},
         "$.method.colour: unknown key for texture-advection"},
        {"spot-noise", "count", std::int64_t{0}, "$.method.count: expected an integer from 1"},
        {"spot-noise", "iso", std::string("high"), "$.method.iso: expected a number"},
        {"spot-noise", "band", -1.0, "$.method.band: expected a number > 0"},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(std::string(c.method) + " " + c.key);
        Scene scene = flow_scene(0.0);
        scene.camera = top_camera(true);
        MethodSpec m;
        m.name = c.method;
        m.options["vectors"] = std::string("velocity");
        if (std::string(c.method) == "spot-noise" && std::string(c.key) != "iso") {
            m.options["iso"] = 0.0;
        }
        m.options[c.key] = c.value;
        scene.method = m;
        Pipeline pipeline;
        const Status checked = pipeline.check(scene);
        ASSERT_FALSE(checked.ok());
        const std::string line = checked.error().to_string();
        EXPECT_EQ(line.rfind("flow.scene.json: error: ", 0), 0u) << line;
        EXPECT_NE(line.find(c.says), std::string::npos) << line;
        EXPECT_EQ(line.find('\n'), std::string::npos) << line;
    }
}

// What only loading finds: a slice that misses the mesh, an iso outside the scalar's range,
// a vector array that is not there, a missing key.
TEST(FlowtexSceneBadInput, SliceMissingTheMeshAndIsoOutsideTheRange) {
    struct Case {
        MethodSpec method;
        const char* says;
    };
    std::vector<Case> cases;
    MethodSpec m = advection_method({{0, 0, -1, 0, 0, 1}, {0, 0, 9, 0, 0, 1}}, 2, 0.5);
    cases.push_back({m, "$.method.slices[1]: "});
    m.options["vectors"] = std::string("wind");
    cases.push_back({m, "$.method.vectors: "});
    MethodSpec spots;
    spots.name = "spot-noise";
    spots.options["vectors"] = std::string("velocity");
    spots.options["iso"] = 7.5;
    cases.push_back({spots, "$.method.iso: "});
    spots.options.erase("iso");
    cases.push_back({spots, "$.method.iso: missing"});
    for (const Case& c : cases) {
        Scene scene = flow_scene(0.0);
        scene.camera = top_camera(true);
        scene.method = c.method;
        Pipeline pipeline;
        const auto result = pipeline.render(scene);
        ASSERT_FALSE(result.ok());
        const std::string line = result.error().to_string();
        SCOPED_TRACE(line);
        EXPECT_EQ(line.rfind("flow.scene.json: error: ", 0), 0u);
        EXPECT_NE(line.find(c.says), std::string::npos);
        EXPECT_EQ(line.find('\n'), std::string::npos);
    }
}

// Layers whose pictures would not fit the memory budget: one line, before any is made.
TEST(FlowtexSceneBadInput, LayersBeyondTheMemoryBudget) {
    NumberLists slices;
    for (int i = 0; i < 16; ++i) slices.push_back({0, 0, -1.5 + 0.2 * i, 0, 0, 1});
    Scene scene = flow_scene(0.0);
    scene.camera = top_camera(true);
    scene.method = advection_method(slices, 2, 0.5);
    set_memory_budget(1 << 20);  // 96^2 pixels x 16 layers take about 5 MB
    Pipeline pipeline;
    const auto result = pipeline.render(scene);
    set_memory_budget(0);
    ASSERT_FALSE(result.ok());
    const std::string line = result.error().to_string();
    EXPECT_EQ(line.rfind("flow.scene.json: error: 16 layers over a 96x96 picture would take", 0),
              0u)
        << line;
}

}  // namespace
}  // namespace tr
