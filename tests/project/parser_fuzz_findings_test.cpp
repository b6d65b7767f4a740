// Inputs the fuzz targets found (fuzz/, docs/fuzzing.md), each pinned: the scene and colour-map
// preset parsers must return a one-line error, never throw.
#include <pipeline/scene.h>
#include <project/colormap_preset.h>

#include <gtest/gtest.h>

#include <string>

namespace tr {
namespace {

bool one_line(const std::string& s) { return !s.empty() && s.find('\n') == std::string::npos; }

// fuzz_scene, first minute: "1e4005" made nlohmann::json throw out_of_range.406 ("number
// overflow"), which parse_scene did not catch (terminate under the fuzzer; "internal error:
// [json.exception.out_of_range.406] ..." from the CLI, the issue's `"width": 1e400`).
TEST(ParserFuzzFindings, SceneNumberBeyondADoubleIsAnError) {
    for (const std::string text :
         {"1e4005", "{\"image\": {\"width\": 1e400, \"height\": 2}}", "[-1e309]"}) {
        SCOPED_TRACE(text);
        auto scene = parse_scene(text, "/nonexistent", "fuzz.json");
        ASSERT_FALSE(scene.ok());
        EXPECT_EQ(scene.error().code, ErrorCode::kParse);
        EXPECT_TRUE(one_line(scene.error().to_string())) << scene.error().to_string();
        EXPECT_NE(scene.error().message.find("beyond a double"), std::string::npos)
            << scene.error().message;
        EXPECT_EQ(scene.error().message.find("json.exception"), std::string::npos)
            << scene.error().message;
    }
}

TEST(ParserFuzzFindings, PresetNumberBeyondADoubleIsAnError) {
    for (const std::string text :
         {"1e4005", "[{\"Name\": \"a\", \"RGBPoints\": [0, 0, 0, 0, 1e400, 1, 1, 1]}]"}) {
        SCOPED_TRACE(text);
        auto presets = parse_colormap_presets(text, "fuzz.json");
        ASSERT_FALSE(presets.ok());
        EXPECT_EQ(presets.error().code, ErrorCode::kParse);
        EXPECT_TRUE(one_line(presets.error().to_string())) << presets.error().to_string();
        EXPECT_NE(presets.error().message.find("beyond a double"), std::string::npos)
            << presets.error().message;
    }
}

}  // namespace
}  // namespace tr
