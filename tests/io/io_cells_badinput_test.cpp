// Cell data VTK trusts (issue 13): polyhedron cells, whose face stream VTK decodes without
// bounds (a face count past the list crashed it, legacy 4.2 and 5.1 and XML alike), and a
// .pvtu whose PPoints type disagrees with its piece's (VTK reinterprets the bytes: garbage
// coordinates, exit 0). Each must be a one-line error naming the file.

#include <io/read_mesh.h>
#include <tests/io/io_test_util.h>

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

namespace tr {
namespace {

namespace fs = std::filesystem;

using test::expect_error;
using test::TempDir;
using test::write_file;

std::string replaced(std::string text, const std::string& from, const std::string& to) {
    const std::size_t at = text.rfind(from);
    if (at == std::string::npos) throw std::logic_error("test setup: no '" + from + "'");
    return text.replace(at, from.size(), to);
}

TEST(BadInputCells, PolyhedronCellsAreRefusedBeforeVtk) {
    TempDir dir;
    // mixed_mesh()'s cell 2 is a pyramid (type 14): make it a polyhedron.
    test::LegacyLayout ascii;
    test::LegacyLayout binary;
    binary.header = "# vtk DataFile Version 4.2\ntest\nBINARY\n";
    binary.binary = true;
    test::LegacyLayout v51 = ascii;
    v51.header = "# vtk DataFile Version 5.1\ntest\nASCII\n";
    v51.offsets_cells = true;
    const std::string binary_text = test::legacy_unstructured(binary);
    const std::string types = "CELL_TYPES 4\n";
    const std::size_t pyramid_type = binary_text.find(types) + types.size() + 8;
    std::string binary_42 = binary_text;
    binary_42.replace(pyramid_type, 4, std::string("\0\0\0\x2a", 4));
    const struct {
        std::string name;
        std::string bytes;
        std::string message_part;
    } cases[] = {
        {"ascii42.vtk", replaced(test::legacy_unstructured(ascii), "12 13 14 10", "12 13 42 10"),
         "CELL_TYPES: cell 2 is a polyhedron (type 42)"},
        {"v51_42.vtk", replaced(test::legacy_unstructured(v51), "12 13 14 10", "12 13 42 10"),
         "CELL_TYPES: cell 2 is a polyhedron (type 42)"},
        {"binary42.vtk", binary_42, "CELL_TYPES: cell 2 is a polyhedron (type 42)"},
        {"faces.vtu",
         replaced(test::vtu_ascii(test::mixed_mesh(), {}, {}), "</Cells>",
                  "<DataArray type=\"Int64\" Name=\"faces\" format=\"ascii\">65544 1 2"
                  "</DataArray><DataArray type=\"Int64\" Name=\"faceoffsets\" "
                  "format=\"ascii\">-1 -1 -1 3</DataArray></Cells>"),
         "polyhedron cells (a 'faces' array) are not supported"},
    };
    for (const auto& c : cases) {
        SCOPED_TRACE(c.name);
        const fs::path path = dir / c.name;
        write_file(path, c.bytes);
        const std::string message = expect_error(read_mesh(path), path);
        EXPECT_NE(message.find(c.message_part), std::string::npos) << message;
    }
    // The same files with the pyramid kept read (the check refuses type 42 only).
    write_file(dir / "binary.vtk", binary_text);
    auto ok = read_mesh(dir / "binary.vtk");
    ASSERT_TRUE(ok.ok()) << ok.error().to_string();
    EXPECT_EQ(ok.value().num_cells(), 4u);
}

TEST(BadInputCells, PvtuPointTypeMustMatchItsPieces) {
    TempDir dir;
    // vtu_ascii stores Float64 points.
    write_file(dir / "piece.vtu", test::vtu_ascii(test::mixed_mesh(), {}, {}));
    const auto pvtu = [](const std::string& type) {
        return "<?xml version=\"1.0\"?>\n<VTKFile type=\"PUnstructuredGrid\" version=\"1.0\">\n"
               "<PUnstructuredGrid GhostLevel=\"0\">\n<PPoints><PDataArray type=\"" +
               type +
               "\" NumberOfComponents=\"3\"/></PPoints>\n<Piece Source=\"piece.vtu\"/>\n"
               "</PUnstructuredGrid>\n</VTKFile>\n";
    };
    write_file(dir / "float32.pvtu", pvtu("Float32"));
    const std::string message = expect_error(read_mesh(dir / "float32.pvtu"), dir / "float32.pvtu");
    EXPECT_NE(message.find("PPoints declares Float32 points, but piece 'piece.vtu' stores Float64"),
              std::string::npos)
        << message;
    write_file(dir / "float64.pvtu", pvtu("Float64"));
    auto ok = read_mesh(dir / "float64.pvtu");
    ASSERT_TRUE(ok.ok()) << ok.error().to_string();
    EXPECT_NEAR(test::total_abs_volume(ok.value()), 1.0 + 1.0 / 6 + 0.5 + 1.0 / 3, 1e-12);
}

}  // namespace
}  // namespace tr
