// tetrender advect on the shared data's vector fields (office, carotid, disk_out_ref,
// combustor): both methods write every frame and the texture moves.
#include <tests/apps/cli_runner.h>
#include <tests/support/sanitized.h>
#include <tests/support/temp_dir.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <ostream>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

namespace tr {
namespace {

struct Case {
    const char* file;
    const char* vectors;
};

void PrintTo(const Case& c, std::ostream* os) { *os << c.file; }

const Case kCases[] = {
    {"office/office.binary.vtk", "vectors"},
    {"carotid/carotid.vtk", "vectors"},
    {"disk_out_ref/disk_out_ref.ex2", "V"},
    {"combustor/combustor.vtu", "Velocity"},
};

std::string bytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

class AdvectRealData : public ::testing::TestWithParam<Case> {};

TEST_P(AdvectRealData, BothMethodsWriteMovingFrames) {
    if (!testing::require_shared_data()) GTEST_SKIP() << "no shared data";
    const Case& c = GetParam();
    const testing::TempDir temp;
    const std::string dir = temp.string();
    const std::string mesh =
        testing::shell_quote((std::filesystem::path(testing::shared_data_dir()) / c.file).string());
    for (const char* method : {"backward", "forward"}) {
        const std::string frames = dir + "/" + method;
        const auto run = testing::run_cli("advect " + mesh + " --vectors " + c.vectors +
                                          " --steps 4 --size 64x64 " + "--resolution 48 --method " +
                                          method + " --frames " + testing::shell_quote(frames));
        ASSERT_EQ(run.exit_code, 0) << run.err;
        EXPECT_NE(run.out.find("wrote 5 frames"), std::string::npos) << run.out;
        const std::string first = bytes(frames + "/frame_0000.png");
        const std::string last = bytes(frames + "/frame_0004.png");
        EXPECT_FALSE(first.empty());
        EXPECT_TRUE(first != last) << method << ": the texture did not move";
    }
}

INSTANTIATE_TEST_SUITE_P(Shared, AdvectRealData, ::testing::ValuesIn(kCases));

// The scene methods over the same data: a volume with two sheets, or spot noise near a contour
// of the scene's scalar; `render --frames` writes moving frames, and the sheets or spots show
// over the volume (the picture is not the volume alone's).
struct SceneCase {
    const char* file;
    const char* scalar;
    double lo, hi;     // the scalar's range
    double centre[3];  // of the bounds
    double extent;     // the bounds' largest side
};

void PrintTo(const SceneCase& c, std::ostream* os) { *os << c.file; }

const std::vector<SceneCase> kSceneCases = {
    {"office/office.binary.vtk", "scalars", -3.87, 0.72, {2.25, 2.25, 1.25}, 4.5},
    {"carotid/carotid.vtk", "scalars", 0, 580, {137.5, 104, 23}, 75},
};

class AdvectSceneRealData : public ::testing::TestWithParam<SceneCase> {};

TEST_P(AdvectSceneRealData, SheetsAndSpotsOverTheVolume) {
    if (!testing::require_shared_data()) GTEST_SKIP() << "no shared data";
    const SceneCase& c = GetParam();
    const testing::TempDir temp;
    const std::string dir = temp.string();
    const std::string mesh = (std::filesystem::path(testing::shared_data_dir()) / c.file).string();
    const double x = c.centre[0], y = c.centre[1], z = c.centre[2], d = c.extent;
    const double mid = 0.5 * (c.lo + c.hi);
    auto scene = [&](const std::string& name, const std::string& method) {
        const std::string path = dir + "/" + name + ".scene.json";
        std::ofstream(path) << "{\"mesh\": \"" << mesh << "\", \"scalar\": \"" << c.scalar
                            << "\", \"transfer_function\": {\"color\": [[" << c.lo
                            << ", 0.1, 0.2, 0.7], [" << c.hi << ", 1, 0.6, 0.2]], \"opacity\": [["
                            << c.lo << ", 0], [" << c.hi << ", 0.3]], \"unit_distance\": " << d / 10
                            << "}, \"camera\": {\"position\": [" << x + 2 * d << ", " << y - 1.5 * d
                            << ", " << z + 1.2 * d << "], \"focal_point\": [" << x << ", " << y
                            << ", " << z
                            << "], \"view_up\": [0, 0, 1]}, \"image\": {\"width\": 64, "
                               "\"height\": 48}"
                            << method << "}\n";
        return testing::shell_quote(path);
    };
    const std::string plain = dir + "/plain.png";
    auto run = testing::run_cli("render " + scene("plain", "") + " -o " + plain);
    ASSERT_EQ(run.exit_code, 0) << run.err;
    std::ostringstream slices;
    slices << "[[" << x << ", " << y << ", " << z - d / 8 << ", 0, 0, 1], [" << x << ", " << y
           << ", " << z + d / 8 << ", 0, 0, 1]]";
    const std::string methods[] = {
        ", \"method\": {\"name\": \"texture-advection\", \"vectors\": \"vectors\", \"steps\": 3, "
        "\"resolution\": 48, \"slices\": " +
            slices.str() + "}",
        ", \"method\": {\"name\": \"spot-noise\", \"vectors\": \"vectors\", \"steps\": 3, "
        "\"count\": 3000, \"iso\": " +
            std::to_string(mid) + "}"};
    for (const std::string& method : methods) {
        SCOPED_TRACE(method);
        const std::string frames = dir + "/frames";
        std::filesystem::remove_all(frames);
        run = testing::run_cli("render " + scene("method", method) + " --frames " +
                               testing::shell_quote(frames));
        ASSERT_EQ(run.exit_code, 0) << run.err;
        const std::string first = bytes(frames + "/frame_0000.png");
        const std::string last = bytes(frames + "/frame_0003.png");
        EXPECT_FALSE(first.empty());
        EXPECT_TRUE(first != last) << "the texture did not move";
        EXPECT_TRUE(last != bytes(plain)) << "nothing over the volume";
    }
}

// In the sanitizer build (tests/support/sanitized.h) the office alone: carotid takes 36 s there.
INSTANTIATE_TEST_SUITE_P(
    Shared, AdvectSceneRealData,
    ::testing::ValuesIn(testing::sanitized_subset(kSceneCases, [](const SceneCase& c) {
        return std::string_view(c.file).starts_with("office");
    })));

}  // namespace
}  // namespace tr
