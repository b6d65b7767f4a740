#pragma once
// Helpers for the io tests: a temporary folder, hand-written files in the formats io/ reads
// (VTK XML ASCII, legacy ASCII and binary), cell volumes, shared data lookup.

#include <core/result.h>
#include <mesh/unstructured_mesh.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace tr::test {

namespace fs = std::filesystem;

// A fresh folder under the system temp dir, removed at destruction.
class TempDir {
  public:
    TempDir();
    ~TempDir();
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
    const fs::path& path() const { return path_; }
    fs::path operator/(const std::string& name) const { return path_ / name; }

  private:
    fs::path path_;
};

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

// Signed volume of a linear cell (tet, hex, wedge, pyramid) from its outward faces; positive
// for VTK's orientation.
double cell_volume(const UnstructuredMesh& mesh, std::size_t cell);
// Sum of |cell_volume| over all cells.
double total_abs_volume(const UnstructuredMesh& mesh);

// True when the message is one non-empty line.
bool one_line(const std::string& message);

// Shared data folder (TETRENDER_SHARED_DATA_DIR), or empty when absent.
fs::path shared_data_dir();

}  // namespace tr::test
