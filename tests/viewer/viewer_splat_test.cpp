// The viewer's splat mode (issue 14): the headless picture of a lattice is `tetrender render
// --method splat`'s bit for bit (both are the library's CPU picture), and with --vectors frame i
// of a headless run is frame i mod N of the texture cycle the CLI writes, so that the cycle
// plays in the window; bad splat options are one line.
#include <tests/apps/cli_runner.h>
#include <tests/support/image_check.h>
#include <tests/support/temp_dir.h>
#include <tests/viewer/viewer_runner.h>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

namespace tr {
namespace {

using testing::read_pfm;
using testing::require_xvfb;
using testing::run_cli;
using testing::run_viewer;
using testing::shell_quote;

// A 13^3 lattice on [0, 4]^3 (legacy ASCII structured points) with the height `h` as scalar
// and a swirl `velocity` = (2 - y, x - 2, 0.3).
std::string write_lattice(const std::string& dir) {
    const int n = 13;
    const double step = 4.0 / (n - 1);
    std::string s = "# vtk DataFile Version 3.0\nswirl\nASCII\nDATASET STRUCTURED_POINTS\n";
    s += "DIMENSIONS 13 13 13\nORIGIN 0 0 0\nSPACING " + std::to_string(step) + " " +
         std::to_string(step) + " " + std::to_string(step) + "\nPOINT_DATA 2197\n";
    std::string h = "SCALARS h float 1\nLOOKUP_TABLE default\n", v = "VECTORS velocity float\n";
    for (int k = 0; k < n; ++k) {
        for (int j = 0; j < n; ++j) {
            for (int i = 0; i < n; ++i) {
                const double x = i * step, y = j * step, z = k * step;
                h += std::to_string(z) + "\n";
                v += std::to_string(2 - y) + " " + std::to_string(x - 2) + " 0.3\n";
            }
        }
    }
    const std::string path = dir + "/swirl.vtk";
    std::ofstream(path) << s << h << v;
    return path;
}

std::string bytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(ViewerSplat, TheHeadlessPictureIsRendersAndTheCyclePlays) {
    if (!require_xvfb()) GTEST_SKIP() << "no xvfb-run";
    const testing::TempDir temp;
    const std::string dir = temp.string();
    const std::string lattice = shell_quote(write_lattice(dir));
    const std::string quick = " --scalar h --size 160x120 ";
    // Scalar splats: the same picture, bit for bit, legend (render's, on for a mesh) and all.
    auto run =
        run_cli("render " + lattice + quick + "--method splat -o " + shell_quote(dir + "/cpu.pfm"));
    ASSERT_EQ(run.exit_code, 0) << run.err;
    run =
        run_viewer(lattice + quick + "--method splat --screenshot " + shell_quote(dir + "/gl.pfm"));
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_NE(run.err.find("splat:"), std::string::npos) << run.err;
    const Image cpu = read_pfm(dir + "/cpu.pfm"), gl = read_pfm(dir + "/gl.pfm");
    ASSERT_EQ(gl.width, 160);
    EXPECT_EQ(gl.pixels, cpu.pixels);
    EXPECT_GT(testing::lit_fraction(cpu, 0.05f), 0.1);
    // Vector splats: the CLI's 4 frames of the cycle, and 6 viewer frames (no orbit).
    run = run_cli("render " + lattice + quick + "--method splat --vectors velocity --cycle 4 " +
                  "--frames " + shell_quote(dir + "/cli"));
    ASSERT_EQ(run.exit_code, 0) << run.err;
    run = run_viewer(lattice + quick + "--method splat --vectors velocity --cycle 4 --frames 6 " +
                     "--frames-dir " + shell_quote(dir + "/view") + " --screenshot " +
                     shell_quote(dir + "/last.png"));
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const auto frame = [&](const std::string& folder, int k) {
        char name[32];
        std::snprintf(name, sizeof name, "/frame_%04d.png", k);
        return bytes(dir + "/" + folder + name);
    };
    for (int i = 0; i < 6; ++i) {
        ASSERT_FALSE(frame("view", i).empty()) << i;
        EXPECT_EQ(frame("view", i), frame("cli", i % 4)) << "viewer frame " << i;
    }
    EXPECT_NE(frame("view", 1), frame("view", 0));  // the streaks move
    // Bad options: one line each.
    for (const std::string& bad :
         {std::string(" --method splat --vectors h"), std::string(" --vectors velocity"),
          std::string(" --method splat --vectors nope")}) {
        run = run_viewer(lattice + quick + bad + " --screenshot " + shell_quote(dir + "/x.png"));
        EXPECT_NE(run.exit_code, 0) << bad;
        EXPECT_EQ(run.err.find('\n'), run.err.size() - 1) << bad << ": " << run.err;
        EXPECT_FALSE(std::filesystem::exists(dir + "/x.png")) << bad;
    }
}

}  // namespace
}  // namespace tr
