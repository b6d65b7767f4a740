// The viewer's colour legend (ImGui): drawn at the window's right edge when on (the default),
// gone with --legend off, never in a plain headless screenshot (those stay equal to the CPU
// renderer's picture), and a bad --legend value refused in one line.
#include <apps/viewer/viewer_scene.h>
#include <mesh/point_data.h>
#include <tests/support/image_check.h>
#include <tests/viewer/viewer_runner.h>
#include <tests/viewer/viewer_test_scene.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

namespace tr {
namespace {

using testing::read_pfm;
using testing::require_xvfb;
using testing::run_viewer;
using testing::shell_quote;

// Pixels that differ by more than half an 8-bit level, counted in columns [x0, x1).
int differing(const Image& a, const Image& b, int x0, int x1) {
    int n = 0;
    for (int y = 0; y < a.height; ++y) {
        for (int x = x0; x < x1; ++x) {
            const Vec3f d = glm::abs(a.at(x, y) - b.at(x, y));
            if (std::max({d.x, d.y, d.z}) > 0.5f / 255) ++n;
        }
    }
    return n;
}

TEST(ViewerLegend, OnByDefaultOffWhenAskedNeverInAPlainScreenshot) {
    if (!require_xvfb()) GTEST_SKIP() << "no xvfb-run";
    const testing::TestScene t = testing::make_test_scene();
    auto shot = [&](const std::string& options, const std::string& name) {
        const std::string path = t.dir + "/" + name + ".pfm";
        const auto run =
            run_viewer(shell_quote(t.scene) + " " + options + " --screenshot " + shell_quote(path));
        EXPECT_EQ(run.exit_code, 0) << run.err;
        return read_pfm(path);
    };
    const Image with = shot("--panel-in-screenshot", "with");
    const Image without = shot("--panel-in-screenshot --legend off", "without");
    const Image plain_on = shot("--legend on", "plain_on");
    const Image plain_off = shot("--legend off", "plain_off");
    ASSERT_EQ(with.width, 240);
    ASSERT_EQ(without.width, 240);
    // The legend's bar, labels and backing in the right quarter of the picture.
    const int right = differing(with, without, 180, 240);
    std::printf("legend: %d pixels differ in the right quarter\n", right);
    EXPECT_GT(right, 4500);  // measured 5878 (Mesa llvmpipe, ImGui default font), less 23%
    // Plain headless screenshots have no ImGui: bit-identical either way.
    ASSERT_EQ(plain_on.width, 240);
    EXPECT_EQ(plain_on.pixels, plain_off.pixels);
}

TEST(ViewerLog, ShowsTheDecadesOfTheMeshScalar) {
    const testing::TestScene t = testing::make_test_scene(6);
    viewer::ViewerOptions options;
    options.input = t.mesh;
    options.quick.scalar = "blob";
    options.quick.log_scale = true;
    auto loaded = viewer::load_viewer_scene(options);
    ASSERT_TRUE(loaded.ok()) << loaded.error().to_string();
    const viewer::ViewerScene& vs = *loaded;
    EXPECT_TRUE(vs.log_scale);
    // The shown scalar is log10 of the field, values <= 0 as the smallest positive one.
    const std::vector<float> field = point_scalar(vs.sort.mesh(), "blob", -1).value();
    float smallest = 1e30f, largest = 0.0f;
    std::size_t not_positive = 0;
    for (std::size_t p = 0; p < vs.sort.mesh().num_points(); ++p) {
        if (field[p] > 0.0f) {
            smallest = std::min(smallest, field[p]);
            largest = std::max(largest, field[p]);
        } else {
            ++not_positive;
        }
    }
    EXPECT_GT(not_positive, 0u);  // the blob goes negative: the clamp is exercised
    for (std::size_t p = 0; p < vs.sort.mesh().num_points(); ++p) {
        ASSERT_FLOAT_EQ(vs.scalar[p], std::log10(std::max(field[p], smallest))) << p;
    }
    // The editor's axis is in decades, inside the shown values' range.
    EXPECT_GE(vs.edit.lo, std::log10(smallest) - 1e-6);
    EXPECT_LE(vs.edit.hi, std::log10(largest) + 1e-6);
    EXPECT_GT(vs.edit.hi, vs.edit.lo);
    // A scene file's transfer function is its own.
    options.input = t.scene;
    const auto scene = viewer::load_viewer_scene(options);
    ASSERT_FALSE(scene.ok());
    EXPECT_NE(scene.error().message.find("--log is for a mesh file"), std::string::npos);
}

TEST(ViewerLegend, BadValueIsRefusedInOneLine) {
    const testing::TestScene t = testing::make_test_scene(4);
    const auto run = run_viewer(
        shell_quote(t.scene) + " --legend maybe --screenshot " + shell_quote(t.dir + "/x.pfm"),
        /*xvfb=*/false);
    EXPECT_NE(run.exit_code, 0);
    EXPECT_NE(run.err.find("--legend"), std::string::npos) << run.err;
    EXPECT_FALSE(std::filesystem::exists(t.dir + "/x.pfm"));
}

}  // namespace
}  // namespace tr
