#pragma once
// Helpers for the io tests: a temporary folder, hand-written files in the formats io/ reads
// (VTK XML ASCII, legacy ASCII and binary), cell volumes, shared data lookup, error checks.

#include <core/result.h>
#include <mesh/unstructured_mesh.h>
#include <tests/support/temp_dir.h>

#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace tr::test {

namespace fs = std::filesystem;

// A fresh folder under the system temp dir, removed at destruction (tests/support/temp_dir.h).
using TempDir = ::tr::testing::TempDir;

void write_file(const fs::path& path, const std::string& bytes);
std::string read_file(const fs::path& path);

// A data array for the hand-written VTK files: type "Float32", "Float64", "Int32", ...
struct TestArray {
    std::string name;
    std::string type;
    int num_components = 1;
    std::vector<double> values;
};

// Small meshes: one unit cube as a hexahedron plus a tetrahedron and a wedge and a pyramid on
// its sides (12 points, 4 cells of volume 1 + 1/6 + 1/2 + 1/3).
UnstructuredMesh mixed_mesh();

// VTK XML ASCII .vtu of a mesh with the given arrays.
std::string vtu_ascii(const UnstructuredMesh& mesh, const std::vector<TestArray>& point_arrays,
                      const std::vector<TestArray>& cell_arrays);
// Legacy ASCII (version 4.2, "CELLS n size") unstructured grid.
std::string legacy_ascii(const UnstructuredMesh& mesh, const std::vector<TestArray>& point_arrays,
                         const std::vector<TestArray>& cell_arrays);
// Legacy BINARY (big-endian, version 4.2) unstructured grid with float32 points.
std::string legacy_binary(const UnstructuredMesh& mesh);

// How a hand-written legacy file is laid out, for the header-variant tests: everything before
// DATASET verbatim, then body lines ended by `eol` (before BINARY data it must end in exactly
// one '\n', as VTK reads one line before the bytes), `gap` after each data block.
struct LegacyLayout {
    std::string header = "# vtk DataFile Version 3.0\ntest\nASCII\n";
    bool binary = false;          // must match the header's ASCII / BINARY
    std::string eol = "\n";       // ends each keyword line
    std::string gap;              // after each data block (blank lines, blanks)
    bool lower_keywords = false;  // "dataset structured_points", "point_data", ...
    bool aspect_ratio = false;    // VTK 1.0's ASPECT_RATIO instead of SPACING
    bool offsets_cells = false;   // VTK 5.1's CELLS with OFFSETS and CONNECTIVITY arrays
};

// Legacy STRUCTURED_POINTS 3 x 2 x 2, origin (1, 2, 3), spacing (0.5, 1, 2): point data `temp`
// (float, point i has 1.5 i) and `vel` (float vectors, component k of point i is 3 i + k), cell
// data `cell_id` (int, 10 and 20).
std::string legacy_points_grid(const LegacyLayout& layout);
// Legacy UNSTRUCTURED_GRID of mixed_mesh() (float points; CELLS n size, or VTK 5.1's OFFSETS
// and CONNECTIVITY as vtktypeint64) with point data `temp` (float, point i has 1.5 i).
std::string legacy_unstructured(const LegacyLayout& layout);

// Signed volume of a linear cell (tet, hex, wedge, pyramid) from its outward faces; positive
// for VTK's orientation.
double cell_volume(const UnstructuredMesh& mesh, std::size_t cell);
// Sum of |cell_volume| over all cells.
double total_abs_volume(const UnstructuredMesh& mesh);

// True when the message is one non-empty line.
bool one_line(const std::string& message);

// Shared data folder (TETRENDER_SHARED_DATA_DIR), or empty when absent.
fs::path shared_data_dir();

// Whether the shared data folder is there. When it is not: false, and with CI=true also a test
// failure (realdata tests must run in CI). Use TR_REQUIRE_SHARED_DATA() in a test body.
bool require_shared_data();

// Checks that `result` is an error with a one-line message whose `where` names `path`'s file;
// returns the message ("" when it was not an error).
template <class T>
std::string expect_error(const Result<T>& result, const fs::path& path) {
    EXPECT_FALSE(result.ok());
    if (result.ok()) return {};
    const Error& e = result.error();
    EXPECT_TRUE(one_line(e.message)) << "[" << e.message << "]";
    EXPECT_TRUE(one_line(e.to_string())) << "[" << e.to_string() << "]";
    EXPECT_NE(e.where.find(path.filename().string()), std::string::npos)
        << "where '" << e.where << "' should name " << path;
    return e.message;
}

}  // namespace tr::test

// In a test body: skips the test with a message when the shared data folder is absent (and
// fails it too when CI=true).
#define TR_REQUIRE_SHARED_DATA()                                                        \
    do {                                                                                \
        if (!::tr::test::require_shared_data()) {                                       \
            GTEST_SKIP() << "shared data folder absent: " << TETRENDER_SHARED_DATA_DIR; \
        }                                                                               \
    } while (false)
