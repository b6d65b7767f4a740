// tetrender advect on the shared data's vector fields (office, carotid, disk_out_ref,
// combustor): both methods write every frame and the texture moves.
#include <tests/apps/cli_runner.h>

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
    const std::string dir = testing::make_temp_dir();
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

}  // namespace
}  // namespace tr
