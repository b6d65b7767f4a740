// tetrender spotnoise on the shared data's vector fields (office, carotid, disk_out_ref,
// combustor): every frame written, the spots move, and bad input is one line with no frames.
#include <tests/apps/cli_runner.h>
#include <tests/support/temp_dir.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <ostream>
#include <string>

namespace tr {
namespace {

struct Case {
    const char* file;
    const char* scalar;
    const char* iso;
    const char* vectors;
};

void PrintTo(const Case& c, std::ostream* os) { *os << c.file; }

const Case kCases[] = {
    {"office/office.binary.vtk", "scalars", "-0.5", "vectors"},
    {"carotid/carotid.vtk", "scalars", "200", "vectors"},
    {"disk_out_ref/disk_out_ref.ex2", "Temp", "400", "V"},
    {"combustor/combustor.vtu", "Density", "0.4", "Velocity"},
};

std::string bytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

std::string mesh_path(const char* file) {
    return testing::shell_quote(
        (std::filesystem::path(testing::shared_data_dir()) / file).string());
}

class SpotNoiseRealData : public ::testing::TestWithParam<Case> {};

TEST_P(SpotNoiseRealData, WritesMovingFrames) {
    if (!testing::require_shared_data()) GTEST_SKIP() << "no shared data";
    const Case& c = GetParam();
    const testing::TempDir temp;
    const std::string frames = temp.string() + "/frames";
    const auto run = testing::run_cli("spotnoise " + mesh_path(c.file) + " --scalar " + c.scalar +
                                      " --iso " + c.iso + " --vectors " + c.vectors +
                                      " --count 3000 --steps 4 --size 64x64 --frames " +
                                      testing::shell_quote(frames));
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_NE(run.out.find("wrote 5 frames"), std::string::npos) << run.out;
    const std::string first = bytes(frames + "/frame_0000.png");
    const std::string last = bytes(frames + "/frame_0004.png");
    EXPECT_FALSE(first.empty());
    EXPECT_TRUE(first != last) << "the spots did not move";
}

INSTANTIATE_TEST_SUITE_P(Shared, SpotNoiseRealData, ::testing::ValuesIn(kCases));

TEST(SpotNoiseRealDataBadInput, OneLineErrorsAndNoFrames) {
    if (!testing::require_shared_data()) GTEST_SKIP() << "no shared data";
    const std::string mesh = mesh_path("disk_out_ref/disk_out_ref.ex2");
    struct Bad {
        std::string args;
        std::string message;
    };
    const Bad cases[] = {
        {"--scalar Temp --iso 4000 --vectors V",
         "iso 4000 is outside 'Temp''s range [293.15, 913.15]"},
        {"--scalar V --iso 1 --vectors V", "'V' has 3 components; --scalar needs a scalar"},
        {"--scalar Tmp --iso 1 --vectors V", "no point array 'Tmp' (scalar arrays: Temp,"},
        {"--scalar Temp --iso 400 --vectors Temp", "no 3-component point array 'Temp'"},
        {"--scalar Temp --iso 400 --vectors V --count 0", "--count"},
        {"--scalar Temp --iso 400 --vectors V --count 10000001", "--count"},
    };
    for (const Bad& bad : cases) {
        const testing::TempDir temp;
        const std::string frames = temp.string() + "/frames";
        const auto run =
            testing::run_cli("spotnoise " + mesh + " " + bad.args +
                             " --steps 1 --size 32x32 --frames " + testing::shell_quote(frames));
        EXPECT_NE(run.exit_code, 0) << bad.args;
        EXPECT_NE(run.err.find(bad.message), std::string::npos) << bad.args << ": " << run.err;
        EXPECT_FALSE(std::filesystem::exists(frames + "/frame_0000.png")) << bad.args;
    }
}

}  // namespace
}  // namespace tr
