// A time series whose field is zero at its first step (a scalar released into a flow, made here
// from a real mesh of ../shared/data): `tetrender render SERIES --time-step all` draws every
// frame with one transfer function whose range covers the whole series (what --write-scene
// writes), the legend is the same in every frame, and the last frame is not saturated in the
// colour map's top colour, as it was when the range came from the first step alone.
#include <io/read_mesh.h>
#include <io/write_image.h>
#include <io/write_vtu.h>
#include <mesh/point_data.h>
#include <mesh/tetrahedralize.h>
#include <tests/apps/cli_runner.h>
#include <tests/support/temp_dir.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

namespace tr {
namespace {

using testing::run_cli;
using testing::shell_quote;

constexpr int kSteps = 3;

// dir/series.pvd: the blunt fin's density times 0, 1/2 and 1 at steps 0, 1, 2 as point array
// "c". Returns the largest density.
double write_series(const std::string& dir) {
    const auto input = read_mesh(testing::shared_data_dir() + "/bluntfin/bluntfin.vtu");
    EXPECT_TRUE(input.ok()) << input.error().to_string();
    const TetMesh mesh = tetrahedralize(input.value()).value();
    const std::vector<float> density = point_scalar(mesh, "Density").value();
    std::ofstream pvd(dir + "/series.pvd");
    pvd << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n"
           "<Collection>\n";
    for (int k = 0; k < kSteps; ++k) {
        TetMesh step = mesh;
        std::vector<float> c(density.size());
        for (std::size_t i = 0; i < c.size(); ++i) c[i] = density[i] * 0.5f * k;
        EXPECT_TRUE(step.add_point_field(make_float_field("c", 1, std::move(c))).ok());
        char name[16];  // (a string sum here trips GCC 12's -Wrestrict false positive)
        std::snprintf(name, sizeof name, "s%d.vtu", k);
        EXPECT_TRUE(write_vtu(step, std::filesystem::path(dir) / name).ok());
        pvd << "<DataSet timestep=\"" << k << "\" file=\"" << name << "\"/>\n";
    }
    pvd << "</Collection>\n</VTKFile>\n";
    return *std::max_element(density.begin(), density.end());
}

Image frame(const std::string& dir, int k) {
    const auto image = read_png(dir + "/frame_000" + std::to_string(k) + ".png");
    EXPECT_TRUE(image.ok()) << image.error().to_string();
    return image.ok() ? image.value() : Image();
}

// The share of the foreground (pixels not the background) in viridis' top colour: yellow, blue
// well below red and green.
double top_colour_share(const Image& image, const Vec3f& background) {
    std::size_t foreground = 0, top = 0;
    for (const Vec3f& p : image.pixels) {
        if (glm::length(p - background) < 0.03f) continue;
        ++foreground;
        if (p.b < 0.45f * std::min(p.r, p.g) && std::abs(p.r - p.g) < 0.3f * std::max(p.r, p.g))
            ++top;
    }
    return foreground == 0 ? 1.0 : static_cast<double>(top) / foreground;
}

TEST(CliSeriesRealData, OneRangeCoversEveryStepOfTheSeries) {
    if (!testing::require_shared_data()) return;
    const testing::TempDir temp;
    const std::string dir = temp.string();
    const double most = write_series(dir);
    const std::string series = shell_quote(dir + "/series.pvd");
    const std::string common = " --scalar c --size 160x120 --time-step all --frames ";
    auto run = run_cli("render " + series + common + shell_quote(dir + "/on") + " --write-scene " +
                       shell_quote(dir + "/scene.json"));
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_NE(run.err.find("the range covers all 3 time steps of 'c'"), std::string::npos)
        << run.err;
    EXPECT_EQ(run.err.find("constant"), std::string::npos) << run.err;  // step 0 is, not 'c'
    // The scene's colours span the series: from its zeros to most of the last step's values.
    const auto scene = nlohmann::json::parse(std::ifstream(dir + "/scene.json"));
    double lo = 1e300, hi = -1e300;
    for (const auto& point : scene["transfer_function"]["color"]) {
        lo = std::min(lo, point[0].get<double>());
        hi = std::max(hi, point[0].get<double>());
    }
    // Measured 0 .. 3.75, the largest density 4.98.
    EXPECT_LE(lo, 0.0);
    EXPECT_GE(hi, 0.5 * most);
    // The legend: the pixels it changes (with --legend off) are the same in every frame where
    // the picture under it is (its text is anti-aliased over the volume).
    run = run_cli("render " + series + common + shell_quote(dir + "/off") + " --legend off");
    ASSERT_EQ(run.exit_code, 0) << run.err;
    std::vector<Image> on, off;
    for (int k = 0; k < kSteps; ++k)
        on.push_back(frame(dir + "/on", k)), off.push_back(frame(dir + "/off", k));
    std::size_t legend = 0, differing = 0;
    for (std::size_t p = 0; p < on[0].pixels.size(); ++p) {
        bool drawn = false;
        for (int k = 0; k < kSteps; ++k) drawn |= on[k].pixels[p] != off[k].pixels[p];
        bool same_under = true;
        for (int k = 1; k < kSteps; ++k) same_under &= off[k].pixels[p] == off[0].pixels[p];
        if (!drawn || !same_under) continue;
        ++legend;
        for (int k = 1; k < kSteps; ++k) differing += on[k].pixels[p] != on[0].pixels[p];
    }
    EXPECT_GT(legend, 1000u);  // measured 1183 (of 1350 the legend changes)
    EXPECT_EQ(differing, 0u);
    // The last step is not saturated in the top colour; with the first step's range it was.
    const Vec3f background = off[0].pixels[0];
    const double share = top_colour_share(off[2], background);
    run = run_cli("render " + series +
                  " --scalar c --size 160x120 --time-step 2 --legend off "
                  "--range -0.5,0.5 -o " +
                  shell_quote(dir + "/old.png"));
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const double old_share = top_colour_share(read_png(dir + "/old.png").value(), background);
    // Measured 0.000 and 1.000: at most a twentieth, and the measure does see saturation.
    EXPECT_LE(share, 0.05);
    EXPECT_GE(old_share, 0.9);
}

}  // namespace
}  // namespace tr
