// ParaView colour-map presets: reading, writing back, the built-in maps, errors with where.
#include <project/colormap.h>
#include <project/colormap_preset.h>
#include <tests/support/temp_dir.h>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

namespace tr {
namespace {

double difference(const Vec3& a, const Vec3& b) {
    return std::max({std::abs(a.r - b.r), std::abs(a.g - b.g), std::abs(a.b - b.b)});
}

TEST(ColormapPreset, WriteThenReadGivesTheSameTransferFunction) {
    const TransferFunction tf =
        TransferFunction::create({{-2.5, {0.1, 0.2, 0.3}},
                                  {0.1, {1.0 / 3, 0.5, 0.0}},
                                  {7.25, {0.9, 0.8, 0.123456789012345}}},
                                 {{-2.5, 0.0}, {1.0, 0.35}, {7.25, 0.9}}, 0.5)
            .value();
    const testing::TempDir temp;
    const auto file = temp / "roundtrip.json";
    ASSERT_TRUE(write_colormap_presets({preset_from_transfer_function(tf, "mine")}, file).ok());
    auto back = read_colormap_preset(file, "mine");
    ASSERT_TRUE(back.ok()) << back.error().to_string();
    EXPECT_EQ(back->color_space, "RGB");
    ASSERT_EQ(back->rgb_points.size(), tf.color_points().size());
    for (std::size_t i = 0; i < back->rgb_points.size(); ++i) {
        EXPECT_EQ(back->rgb_points[i].s, tf.color_points()[i].s);  // bit for bit
        EXPECT_EQ(back->rgb_points[i].rgb, tf.color_points()[i].rgb);
    }
    ASSERT_EQ(back->opacity_points.size(), tf.opacity_points().size());
    for (std::size_t i = 0; i < back->opacity_points.size(); ++i) {
        EXPECT_EQ(back->opacity_points[i].s, tf.opacity_points()[i].s);
        EXPECT_EQ(back->opacity_points[i].a, tf.opacity_points()[i].a);
    }
    EXPECT_TRUE(back->notes.empty());
    // Mapped onto its own range, the colours are the same points.
    const auto colors = preset_colors(*back, -2.5, 7.25);
    ASSERT_EQ(colors.size(), 3u);
    for (std::size_t i = 0; i < 3; ++i) EXPECT_EQ(colors[i].rgb, tf.color_points()[i].rgb);
}

const char* kSample = R"([
  {
    "ColorSpace" : "Lab",
    "Name" : "Dark to Light",
    "NanColor" : [1, 0, 0],
    "RGBPoints" : [0, 0, 0, 0,  1, 1, 1, 1]
  },
  {
    "Name" : "Three",
    "ColorSpace" : "RGB",
    "RGBPoints" : [10, 1, 0, 0,  15, 0, 1, 0,  30, 0, 0, 1],
    "Points" : [10, 0, 0.5, 0,  30, 1, 0.5, 0]
  }
])";

TEST(ColormapPreset, ASampleFileGivesTheColoursAtItsControlPoints) {
    const testing::TempDir temp;
    const auto file = temp / "sample.json";
    std::ofstream(file) << kSample;
    auto three = read_colormap_preset(file, "three");  // case-insensitive
    auto first = read_colormap_preset(file);           // no name: the first
    auto missing = read_colormap_preset(file, "Plasma");
    ASSERT_TRUE(three.ok()) << three.error().to_string();
    EXPECT_EQ(three->name, "Three");
    ASSERT_TRUE(first.ok());
    EXPECT_EQ(first->name, "Dark to Light");
    ASSERT_TRUE(first->nan_color.has_value());

    // Rescaled from [10, 30] to [0, 100]: x = 15 lands at 25.
    const TransferFunction tf =
        TransferFunction::create(preset_colors(*three, 0, 100), preset_opacity(*three, 0, 100), 1.0)
            .value();
    EXPECT_LT(difference(tf.color(0), {1, 0, 0}), 1e-12);
    EXPECT_LT(difference(tf.color(25), {0, 1, 0}), 1e-12);
    EXPECT_LT(difference(tf.color(100), {0, 0, 1}), 1e-12);
    EXPECT_LT(difference(tf.color(12.5), {0.5, 0.5, 0}), 1e-12);  // RGB: linear between
    EXPECT_DOUBLE_EQ(tf.opacity(0), 0.0);
    EXPECT_DOUBLE_EQ(tf.opacity(100), 0.999);  // 1 clamped below 1
    // preset_transfer_function: the preset's own opacity wins; without one, the given ramp.
    auto own = preset_transfer_function(*three, 0, 100, {{0, 0.2}}, 2.0);
    ASSERT_TRUE(own.ok());
    EXPECT_DOUBLE_EQ(own->opacity(100), 0.999);
    EXPECT_EQ(own->unit_distance(), 2.0);
    auto ramp = preset_transfer_function(*first, 0, 100, {{0, 0.0}, {100, 0.3}}, 1.0);
    ASSERT_TRUE(ramp.ok());
    EXPECT_DOUBLE_EQ(ramp->opacity(50), 0.15);
    EXPECT_FALSE(preset_transfer_function(*first, 0, NAN, {{0, 0.0}}, 1.0).ok());

    // Lab between black and white: the middle is L* = 50, sRGB 0.4663 (CIE's formulas: Y =
    // ((50 + 16) / 116)^3 = 0.1842, then the sRGB curve), grey.
    const auto lab = preset_colors(*first, 0, 1);
    const TransferFunction lab_tf = TransferFunction::create(lab, {{0, 0.1}}, 1.0).value();
    const Vec3 mid = lab_tf.color(0.5);
    EXPECT_NEAR(mid.r, 0.4663, 2e-3);
    EXPECT_NEAR(mid.g, mid.r, 1e-3);
    EXPECT_NEAR(mid.b, mid.r, 1e-3);
    EXPECT_LT(difference(lab_tf.color(0), {0, 0, 0}), 1e-6);
    EXPECT_LT(difference(lab_tf.color(1), {1, 1, 1}), 1e-6);

    ASSERT_FALSE(missing.ok());
    EXPECT_NE(missing.error().message.find("'Dark to Light', 'Three'"), std::string::npos)
        << missing.error().to_string();
}

TEST(ColormapPreset, BadJsonIsAOneLineErrorSayingWhere) {
    // Malformed: a missing comma on line 3.
    auto malformed = parse_colormap_presets("[\n {\"Name\": \"a\",\n  \"RGBPoints\": [0, 0 0, 0]}]",
                                            "maps.json");
    ASSERT_FALSE(malformed.ok());
    EXPECT_EQ(malformed.error().where.rfind("maps.json:3:", 0), 0u)
        << malformed.error().to_string();
    EXPECT_EQ(malformed.error().to_string().find('\n'), std::string::npos);
    // Values: a count that is not a multiple of 4, a colour outside [0, 1], decreasing x, no name,
    // an unknown colour space.
    const std::vector<std::pair<std::string, std::string>> cases = {
        {R"([{"Name": "a", "RGBPoints": [0, 0, 0, 0, 1, 1, 1]}])", "$[0].RGBPoints"},
        {R"([{"Name": "a", "RGBPoints": [0, 0, 0, 0]}, {"Name": "b", "RGBPoints": [0, 0, 1.5, 0]}])",
         "$[1].RGBPoints[2]"},
        {R"([{"Name": "a", "RGBPoints": [1, 0, 0, 0, 0, 1, 1, 1]}])", "$[0].RGBPoints[4]"},
        {R"([{"RGBPoints": [0, 0, 0, 0]}])", "$[0].Name"},
        {R"([{"Name": "a", "ColorSpace": "Luv", "RGBPoints": [0, 0, 0, 0]}])", "$[0].ColorSpace"},
        {R"([{"Name": "a", "RGBPoints": [0, 0, "x", 0]}])", "$[0].RGBPoints[2]"},
        {R"({"Name": "a", "IndexedColors": [1, 0, 0]})", "$.RGBPoints"},
        {R"(42)", "$"},
    };
    for (const auto& [text, path] : cases) {
        auto r = parse_colormap_presets(text, "maps.json");
        ASSERT_FALSE(r.ok()) << text;
        EXPECT_EQ(r.error().where, "maps.json");
        EXPECT_EQ(r.error().message.rfind(path + ":", 0), 0u) << r.error().to_string();
        EXPECT_EQ(r.error().to_string().find('\n'), std::string::npos);
    }
}

TEST(ColormapPreset, BuiltInPresetsByParaViewName) {
    for (const std::string& name : builtin_colormap_preset_names()) {
        auto preset = builtin_colormap_preset(name);
        ASSERT_TRUE(preset.ok()) << name;
        auto tf = make_quick_transfer_function(name, 0.0, 1.0, 0.5, 1.0);
        ASSERT_TRUE(tf.ok()) << name << ": " << tf.error().to_string();
        // The ends are the preset's first and last colours.
        EXPECT_LT(difference(tf->color(0.0), preset->rgb_points.front().rgb), 1e-12) << name;
        EXPECT_LT(difference(tf->color(1.0), preset->rgb_points.back().rgb), 1e-12) << name;
    }
    EXPECT_EQ(builtin_colormap_preset_names().size(), 7u);
    EXPECT_TRUE(builtin_colormap_preset("viridis").ok());  // without " (matplotlib)"
    EXPECT_TRUE(builtin_colormap_preset("BLACK-BODY RADIATION").ok());
    EXPECT_FALSE(builtin_colormap_preset("Plasma").ok());

    // Cool to Warm (Diverging): its white middle is exact; between, Moreland's Msh path.
    const auto cool = preset_colors(*builtin_colormap_preset("Cool to Warm"), -1, 1);
    const TransferFunction ctw = TransferFunction::create(cool, {{-1, 0.1}}, 1.0).value();
    EXPECT_LT(difference(ctw.color(0.0), {0.865, 0.865, 0.865}), 1e-12);
    EXPECT_GT(cool.size(), 200u);  // each half split so the whole has about 256 pieces
    // The path stays saturated: at a quarter the colour is bluish, not the RGB average's grey.
    const Vec3 quarter = ctw.color(-0.5);
    EXPECT_GT(quarter.b - quarter.r, 0.15);

    // Viridis: matplotlib's first and last entries.
    const auto v = builtin_colormap_preset("Viridis (matplotlib)").value();
    EXPECT_LT(difference(v.rgb_points.front().rgb, {0.267004, 0.004874, 0.329415}), 1e-12);
    EXPECT_LT(difference(v.rgb_points.back().rgb, {0.993248, 0.906157, 0.143936}), 1e-12);

    // The existing names keep their colours.
    auto old = make_quick_transfer_function("viridis", 0.0, 1.0, 0.5, 1.0);
    ASSERT_TRUE(old.ok());
    EXPECT_LT(difference(old->color(0.0), {0.267, 0.005, 0.329}), 1e-12);
}

}  // namespace
}  // namespace tr
