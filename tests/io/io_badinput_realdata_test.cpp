// Bad input cut from the shared data (/work/shared/data): truncated Exodus files and a time
// step out of range. Each must come back as an Error with a one-line message. Skipped with a
// message when the folder is absent, failing when CI=true.

#include <io/read_mesh.h>
#include <tests/io/io_test_util.h>

#include <gtest/gtest.h>

namespace tr {
namespace {

namespace fs = std::filesystem;

using test::expect_error;
using test::TempDir;
using test::write_file;

TEST(BadInputRealData, TruncatedExodus) {
    TR_REQUIRE_SHARED_DATA();
    const fs::path data = test::shared_data_dir();
    TempDir dir;
    for (const char* name : {"disk_out_ref/disk_out_ref.ex2", "wedge_blocks/mesh_fs8.exo"}) {
        SCOPED_TRACE(name);
        const std::string bytes = test::read_file(data / name);
        ASSERT_FALSE(bytes.empty());
        for (std::size_t keep : {bytes.size() / 2, std::size_t(200), bytes.size() - 100}) {
            SCOPED_TRACE(keep);
            const fs::path path =
                dir / ("cut" + std::to_string(keep) + fs::path(name).extension().string());
            write_file(path, bytes.substr(0, keep));
            expect_error(read_mesh(path), path);
        }
    }
}

TEST(BadInputRealData, ExodusTimeStepOutOfRange) {
    TR_REQUIRE_SHARED_DATA();
    const fs::path exo = test::shared_data_dir() / "disk_out_ref" / "disk_out_ref.ex2";
    for (int step : {1, -1}) {  // the file has one step (0)
        SCOPED_TRACE(step);
        ReadOptions options;
        options.time_step = step;
        auto e = read_mesh(exo, options);
        expect_error(e, exo);
        if (!e.ok()) {
            EXPECT_EQ(e.error().code, ErrorCode::kInvalidArgument);
        }
    }
}

}  // namespace
}  // namespace tr
