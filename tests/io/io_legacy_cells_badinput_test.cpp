// Legacy .vtk cell sections that once crashed or silently became a "point cloud" (issue 13): a
// 4.2 BINARY first cell whose node count is 65544 instead of 8 (crashed tetrender's own code),
// an ASCII CELLS section that fails to parse and one with a connectivity id of 4000000000
// (both were Delaunay-tetrahedralized as a point cloud, exit 0), and a VTK 5.1 BINARY file cut
// at 50% (a point cloud) and at 97% (rendered an array of garbage, exit 0). A mesh is a point
// cloud only when the file says it has no cells: each of these is a one-line error naming the
// file, from read_mesh() and from `tetrender render` (exit 1, no picture written).

#include <io/read_mesh.h>
#include <tests/apps/cli_runner.h>
#include <tests/io/io_test_util.h>

#include <gtest/gtest.h>

#include <cstddef>
#include <stdexcept>
#include <string>

namespace tr {
namespace {

namespace fs = std::filesystem;

using test::expect_error;
using test::TempDir;
using test::write_file;

std::string replaced(std::string text, const std::string& from, const std::string& to) {
    const std::size_t at = text.find(from);
    if (at == std::string::npos) throw std::logic_error("test setup: no '" + from + "'");
    return text.replace(at, from.size(), to);
}

// The first `percent` % of the bytes of `text`.
std::string truncated(const std::string& text, int percent) {
    return text.substr(0, text.size() * static_cast<std::size_t>(percent) / 100);
}

struct BadFile {
    std::string name;
    std::string bytes;
    std::string message_part;  // in the error
};

std::vector<BadFile> bad_files() {
    // mixed_mesh()'s cell 0 is the hexahedron: 8 nodes 0..7, written as "8 0 1 2 3 4 5 6 7".
    const std::string binary = test::legacy_binary(test::mixed_mesh());
    const std::string cells_line = "CELLS 4 ";
    const std::size_t first_count = binary.find('\n', binary.find(cells_line)) + 1;
    std::string count_65544 = binary;
    count_65544.replace(first_count, 4, std::string("\0\1\0\x08", 4));  // big-endian 65544

    test::LegacyLayout ascii;
    ascii.header = "# vtk DataFile Version 4.2\ntest\nASCII\n";
    const std::string ascii_text = test::legacy_unstructured(ascii);

    test::LegacyLayout v51;
    v51.header = "# vtk DataFile Version 5.1\ntest\nBINARY\n";
    v51.binary = true;
    v51.offsets_cells = true;
    const std::string v51_text = test::legacy_unstructured(v51);

    // Messages measured: "CELLS: cell 0 has 65544 points, but its list has 26 entries left",
    // "CELLS: 'x' is not an integer", "CELLS: 'CELL_TYPES' is not an integer", "CELLS:
    // '4000000000' is not an integer", "cannot read legacy VTK file: Unsupported data type:
    // vtktypeint" (VTK's, the cut falls in OFFSETS' type name), "truncated file: SCALARS temp
    // needs 48 bytes, 29 are left".
    return {
        {"count_65544.vtk", count_65544, "cell 0 has 65544 points"},
        {"cells_unparsable.vtk", replaced(ascii_text, "8 0 1 2 3 4 5 6 7", "8 0 1 2 x 4 5 6 7"),
         "CELLS: 'x' is not an integer"},
        {"cells_short.vtk", replaced(ascii_text, "8 0 1 2 3 4 5 6 7", "8 0 1 2"), "CELLS: "},
        {"id_4000000000.vtk",
         replaced(ascii_text, "8 0 1 2 3 4 5 6 7", "8 0 1 2 3 4000000000 5 6 7"),
         "CELLS: '4000000000'"},
        {"v51_cut_50.vtk", truncated(v51_text, 50), "cannot read legacy VTK file"},
        {"v51_cut_97.vtk", truncated(v51_text, 97), "truncated file: SCALARS temp"},
    };
}

TEST(BadInputLegacyCells, ReadMeshRefusesInsteadOfAPointCloud) {
    TempDir dir;
    for (const BadFile& f : bad_files()) {
        SCOPED_TRACE(f.name);
        const fs::path path = dir / f.name;
        write_file(path, f.bytes);
        const std::string message = expect_error(read_mesh(path), path);
        EXPECT_NE(message.find(f.message_part), std::string::npos) << message;
    }
}

TEST(BadInputLegacyCells, UnchangedFilesRead) {
    // The files the bad ones are cut from read, with their cells (so the errors above come from
    // the changes, not from the writers).
    TempDir dir;
    test::LegacyLayout ascii;
    ascii.header = "# vtk DataFile Version 4.2\ntest\nASCII\n";
    test::LegacyLayout v51;
    v51.header = "# vtk DataFile Version 5.1\ntest\nBINARY\n";
    v51.binary = true;
    v51.offsets_cells = true;
    const BadFile good[] = {
        {"binary.vtk", test::legacy_binary(test::mixed_mesh()), ""},
        {"ascii.vtk", test::legacy_unstructured(ascii), ""},
        {"v51.vtk", test::legacy_unstructured(v51), ""},
    };
    for (const BadFile& f : good) {
        SCOPED_TRACE(f.name);
        write_file(dir / f.name, f.bytes);
        auto mesh = read_mesh(dir / f.name);
        ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
        EXPECT_EQ(mesh.value().num_cells(), 4u);
        EXPECT_NEAR(test::total_abs_volume(mesh.value()), 1.0 + 1.0 / 6 + 0.5 + 1.0 / 3, 1e-6);
    }
}

TEST(BadInputLegacyCells, RenderExitsNonZeroWithOneLine) {
    TempDir dir;
    const fs::path png = dir / "out.png";
    for (const BadFile& f : bad_files()) {
        SCOPED_TRACE(f.name);
        const fs::path path = dir / f.name;
        write_file(path, f.bytes);
        const testing::CliRun run =
            testing::run_cli("render " + testing::shell_quote(path.string()) + " -o " +
                             testing::shell_quote(png.string()) + " --scalar temp --size 64x48");
        EXPECT_EQ(run.exit_code, 1) << run.err;                        // not 128 + a signal, not 0
        EXPECT_EQ(run.err.find('\n'), run.err.size() - 1) << run.err;  // one line
        EXPECT_NE(run.err.find(f.name + ":"), std::string::npos) << run.err;
        EXPECT_FALSE(fs::exists(png));
    }
}

}  // namespace
}  // namespace tr
