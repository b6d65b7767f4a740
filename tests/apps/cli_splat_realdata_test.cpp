// The regular grids in ../shared/data splatted (`tetrender render --method splat`) on their
// quick-mode scene: each within a measured PSNR of the projected-tetrahedra picture of the same
// scene (the grid's cells split into linear tets), with both kernels and (the cubic) both
// compositings; the lattice spacing found from the points is the file's.
#include <core/image.h>
#include <tests/apps/cli_runner.h>
#include <tests/support/image_check.h>
#include <tests/support/temp_dir.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

namespace tr {
namespace {

struct Case {
    const char* file;
    const char* scalar;
    double spacing;                        // the file's (SOURCE.md)
    testing::ImageBounds cubic, gaussian;  // against projected tetrahedra, measured - 1.5 dB
    testing::ImageBounds sheet;            // the cubic with the sheet buffer, the same
};

void PrintTo(const Case& c, std::ostream* os) { *os << c.file; }

// Measured at 128 x 96 (foreground PSNR, largest difference): iron_protein 41.68 dB, 0.137
// (cubic), 41.28 dB, 0.157 (Gaussian); carotid 44.87 dB, 0.030 and 44.88 dB, 0.026; the cubic
// with the sheet buffer 41.68 dB, 0.138 and 44.87 dB, 0.030. Bounds 1.5 dB below, the largest
// difference a quarter above.
const Case kCases[] = {
    {"iron_protein/ironProt.vtk", "scalars", 1.0, {40.1, 0.172}, {39.7, 0.197}, {40.1, 0.173}},
    {"carotid/carotid.vtk", "scalars", 1.0, {43.3, 0.038}, {43.3, 0.033}, {43.3, 0.038}},
};

class SplatRealData : public ::testing::TestWithParam<Case> {};

TEST_P(SplatRealData, NearTheProjectedTetrahedraPicture) {
    if (!testing::require_shared_data()) GTEST_SKIP() << "no shared data";
    const Case& c = GetParam();
    const testing::TempDir temp;
    const std::string dir = temp.string();
    const std::string scene = dir + "/scene.json";
    const std::string mesh =
        testing::shell_quote((std::filesystem::path(testing::shared_data_dir()) / c.file).string());
    auto run = testing::run_cli(
        "render " + mesh + " --scalar " + c.scalar +
        // The classic quick look: the measured values below were taken on its scenes.
        " --look classic --size 128x96 --write-scene " + testing::shell_quote(scene) + " -o " +
        testing::shell_quote(dir + "/pt.pfm"));
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const Image pt = testing::read_pfm(dir + "/pt.pfm");
    const std::string name = std::string(c.file).substr(0, std::string(c.file).find('/'));
    for (const char* variant : {"crawfis-max", "gaussian", "sheet-buffer"}) {
        const std::string v = variant;
        const char* kernel = v == "gaussian" ? "gaussian" : "crawfis-max";
        nlohmann::json j = nlohmann::json::parse(std::ifstream(scene));
        j["method"] = {{"name", "splat"},
                       {"kernel", kernel},
                       {"compositing", v == "sheet-buffer" ? "sheet-buffer" : "per-splat"}};
        const std::string splat_scene = dir + "/splat.json";
        std::ofstream(splat_scene) << j.dump();
        run = testing::run_cli("render " + testing::shell_quote(splat_scene) + " --stats -o " +
                               testing::shell_quote(dir + "/splat.pfm"));
        ASSERT_EQ(run.exit_code, 0) << run.err;
        const auto stats = nlohmann::json::parse(run.out);
        EXPECT_NEAR(stats["spacing"].get<double>(), c.spacing, 1e-9);
        EXPECT_GT(stats["splats_drawn"].get<double>(), 1000.0);
        const Image splat = testing::read_pfm(dir + "/splat.pfm");
        const testing::ImageBounds& bounds = v == "gaussian"       ? c.gaussian
                                             : v == "sheet-buffer" ? c.sheet
                                                                   : c.cubic;
        EXPECT_TRUE(
            testing::images_match(splat, pt, Vec3f(0.0f), bounds, "splat_" + v + "_" + name));
    }
}

INSTANTIATE_TEST_SUITE_P(SharedData, SplatRealData, ::testing::ValuesIn(kCases),
                         [](const auto& info) {
                             std::string name = info.param.file;
                             return name.substr(0, name.find('/'));
                         });

std::string slurp(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

// The carotid's velocity as textured vector splats through the command line: --frames writes
// the texture cycle, frame k the single picture of --vectors with that frame; what --vectors
// refuses is a one-line error.
TEST(SplatVectorsRealData, TheCycleOfFramesAndItsErrors) {
    if (!testing::require_shared_data()) GTEST_SKIP() << "no shared data";
    const testing::TempDir temp;
    const std::string dir = temp.string();
    const std::string mesh = testing::shell_quote(
        (std::filesystem::path(testing::shared_data_dir()) / "carotid/carotid.vtk").string());
    const std::string quick = "render " + mesh + " --scalar scalars --size 96x72 --vectors vectors";
    auto run = testing::run_cli(quick + " --cycle 4 --frames " + testing::shell_quote(dir + "/f"));
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_NE(run.err.find("4 frames"), std::string::npos) << run.err;
    EXPECT_FALSE(std::filesystem::exists(dir + "/f/frame_0004.png"));
    run = testing::run_cli(quick + " --cycle 4 -o " + testing::shell_quote(dir + "/one.png"));
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_EQ(slurp(dir + "/f/frame_0000.png"), slurp(dir + "/one.png"));
    for (int k = 1; k < 4; ++k) {
        // The streaks move: every frame differs from the one before.
        EXPECT_NE(slurp(dir + "/f/frame_000" + std::to_string(k) + ".png"),
                  slurp(dir + "/f/frame_000" + std::to_string(k - 1) + ".png"));
    }
    const auto one_line = [](const testing::CliRun& r, int code, const std::string& says) {
        EXPECT_EQ(r.exit_code, code) << r.err;
        EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << r.err;
        EXPECT_NE(r.err.find(says), std::string::npos) << r.err;
    };
    const std::string out = " -o " + testing::shell_quote(dir + "/x.png");
    one_line(testing::run_cli("render " + mesh + " --scalar scalars --vectors scalars" + out), 1,
             "1 component");
    one_line(testing::run_cli(quick + " --orbit 90 --frames " + testing::shell_quote(dir + "/o")),
             2, "does not take --orbit");
    one_line(testing::run_cli(quick + " --sheet-buffer" + out), 2, "--sheet-buffer");
    one_line(testing::run_cli(quick + " --method pbvr-image" + out), 2, "for --method splat");
    EXPECT_FALSE(std::filesystem::exists(dir + "/x.png"));
}

}  // namespace
}  // namespace tr
