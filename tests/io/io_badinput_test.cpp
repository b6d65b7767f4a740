// Bad input for io/: every case must come back as an Error with a one-line message (no crash,
// no exception, no leak; these also run under ASan/UBSan). Cases cut from the shared data:
// io_badinput_realdata_test.cpp.

#include <io/read_mesh.h>
#include <io/read_surface.h>
#include <io/write_vtu.h>
#include <tests/io/io_test_util.h>

#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <random>
#include <stdexcept>
#include <tuple>

namespace tr {
namespace {

namespace fs = std::filesystem;

using test::expect_error;
using test::TempDir;
using test::write_file;

std::string random_bytes(std::size_t n, unsigned seed) {
    std::mt19937 rng(seed);
    std::string s(n, '\0');
    for (char& ch : s) ch = static_cast<char>(rng() & 0xff);
    return s;
}

UnstructuredMesh one_tet() {
    UnstructuredMesh m;
    m.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    m.add_cell(CellType::kTetra, {0, 1, 2, 3});
    return m;
}

TEST(BadInput, MissingFile) {
    TempDir dir;
    const fs::path path = dir / "nothing.vtu";
    auto r = read_mesh(path);
    expect_error(r, path);
    EXPECT_EQ(r.error().code, ErrorCode::kNotFound);
    auto s = read_surface(dir / "nothing.stl");
    ASSERT_FALSE(s.ok());
    EXPECT_EQ(s.error().code, ErrorCode::kNotFound);
}

TEST(BadInput, DirectoryInsteadOfFile) {
    TempDir dir;
    fs::create_directories(dir / "folder.vtu");
    expect_error(read_mesh(dir / "folder.vtu"), dir / "folder.vtu");
}

TEST(BadInput, EmptyFileEveryExtension) {
    TempDir dir;
    for (const std::string& ext : supported_mesh_extensions()) {
        SCOPED_TRACE(ext);
        const fs::path path = dir / ("empty" + ext);
        write_file(path, "");
        const std::string msg = expect_error(read_mesh(path), path);
        EXPECT_NE(msg.find("empty"), std::string::npos) << msg;
    }
    for (const std::string& ext : supported_surface_extensions()) {
        SCOPED_TRACE(ext);
        const fs::path path = dir / ("empty_surface" + ext);
        write_file(path, "");
        expect_error(read_surface(path), path);
    }
}

TEST(BadInput, TruncatedVtu) {
    TempDir dir;
    const std::string text = test::vtu_ascii(test::mixed_mesh(), {}, {});
    const fs::path path = dir / "half.vtu";
    write_file(path, text.substr(0, text.size() / 2));
    expect_error(read_mesh(path), path);
}

TEST(BadInput, TruncatedVtuWithoutClosingTagCheck) {
    // Cut inside the cell arrays but keep a closing tag, so that VTK's parser sees the damage.
    TempDir dir;
    std::string text = test::vtu_ascii(test::mixed_mesh(), {}, {});
    const std::size_t cut = text.find("Name=\"offsets\"");
    ASSERT_NE(cut, std::string::npos);
    text = text.substr(0, cut) + "\n</VTKFile>\n";
    const fs::path path = dir / "cut.vtu";
    write_file(path, text);
    expect_error(read_mesh(path), path);
}

TEST(BadInput, TruncatedLegacyBinary) {
    TempDir dir;
    const std::string bytes = test::legacy_binary(test::mixed_mesh());
    for (std::size_t keep : {bytes.size() / 2, bytes.size() - 10, std::size_t(120)}) {
        SCOPED_TRACE(keep);
        const fs::path path = dir / ("cut" + std::to_string(keep) + ".vtk");
        write_file(path, bytes.substr(0, keep));
        expect_error(read_mesh(path), path);
    }
}

TEST(BadInput, TruncatedLegacyAscii) {
    TempDir dir;
    const std::string text = test::legacy_ascii(test::mixed_mesh(), {}, {});
    const fs::path path = dir / "cut.vtk";
    write_file(path, text.substr(0, text.size() / 2));
    expect_error(read_mesh(path), path);
}

TEST(BadInput, RandomBytesEveryExtension) {
    TempDir dir;
    unsigned seed = 1;
    for (const std::string& ext : supported_mesh_extensions()) {
        for (std::size_t n : {std::size_t(7), std::size_t(300), std::size_t(5000)}) {
            SCOPED_TRACE(ext + " " + std::to_string(n));
            // A folder per case, so that .ele does not find another case's .node.
            const fs::path sub = dir / ("case" + std::to_string(seed));
            fs::create_directories(sub);
            const fs::path path = sub / ("random" + std::to_string(n) + ext);
            write_file(path, random_bytes(n, seed++));
            expect_error(read_mesh(path), path);
        }
    }
    for (const std::string& ext : supported_surface_extensions()) {
        SCOPED_TRACE(ext);
        const fs::path path = dir / ("random_surface" + ext);
        write_file(path, random_bytes(3000, seed++));
        expect_error(read_surface(path), path);
    }
}

TEST(BadInput, ValidHeaderThenGarbage) {
    TempDir dir;
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"a.vtk",
         "# vtk DataFile Version 3.0\nx\nBINARY\nDATASET UNSTRUCTURED_GRID\nPOINTS 1000000000 "
         "float\n"},
        {"b.vtk",
         "# vtk DataFile Version 3.0\nx\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 float\n0 0 0 1 "
         "0 0 0 1 0 0 0 1\n"
         "CELLS 1 5\n4 0 1 2 3\nCELL_TYPES 1\n"},
        {"c.vtk",
         "# vtk DataFile Version 3.0\nx\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 float\n0 0 0 1 "
         "0 0 zz\n"},
        {"d.vtk", "# vtk DataFile Version 3.0\nx\nBANANA\nDATASET UNSTRUCTURED_GRID\n"},
        {"e.vtk", "# vtk DataFile Version 3.0\nx\nASCII\nDATASET NOT_A_TYPE\nPOINTS 4 float\n"},
        {"f.vtu",
         "<?xml version=\"1.0\"?><VTKFile type=\"UnstructuredGrid\"><UnstructuredGrid><Piece "
         "NumberOfPoints=\"99999999999\" "
         "NumberOfCells=\"1\"></Piece></UnstructuredGrid></VTKFile>"},
        {"g.vtu", "<VTKFile type=\"UnstructuredGrid\">" + random_bytes(2000, 99) + "</VTKFile>"},
        {"h.pvd",
         "<VTKFile type=\"Collection\"><Collection><DataSet timestep=\"x\" "
         "file=\"a.vtu\"/></Collection></VTKFile>"},
        {"i.pvd", "<VTKFile type=\"Collection\"><Collection></Collection></VTKFile>"},
        {"j.pvd",
         "<VTKFile type=\"Collection\"><Collection><DataSet timestep=\"0\" "
         "file=\"j.pvd\"/></Collection></VTKFile>"},
        {"k.exo", std::string("CDF\x01", 4) + random_bytes(500, 5)},
        {"l.exo", std::string("\x89HDF\r\n\x1a\n", 8) + random_bytes(500, 6)},
        {"m.csv", "x,y,z\n1,2\n"},
        {"n.csv", "x,y\n1,2\n"},
        {"o.csv", "1,2,3\n4,5,6\n"},
        {"p.csv", "x,y,z\n1,2,abc\n"},
        {"q.mesh",
         "MFEM mesh v1.0\ndimension\n3\nelements\n1\n1 4 0 1 2 3\nvertices\n3\n3\n0 0 0\n1 0 0\n0 "
         "1 0\n"},
        {"r.mesh", "MFEM mesh v1.0\ndimension\n2\n"},
        {"s.mesh", "MFEM NC mesh v1.0\n"},
        {"t.mesh", "MFEM mesh v1.0\ndimension\n3\nelements\n1\n1 9 0 1 2\nvertices\n3\n3\n"},
        {"u.mesh", "MFEM mesh v1.0\ndimension\n3\nelements\n99999999999999\n"},
        {"v.node", "4 3 0 0\n1 0 0 0\n2 1 0 0\n"},
        {"w.node", "4 2 0 0\n"},
        {"x.node", "2 3 0 0\n5 0 0 0\n6 1 0 0\n"},
        {"y.xyz", "xxxxxxxxxxxx"},
        {"z.vts",
         "<VTKFile type=\"StructuredGrid\"><StructuredGrid WholeExtent=\"0 99999 0 99999 0 99999\">"
         "<Piece Extent=\"0 99999 0 99999 0 99999\"><Points><DataArray type=\"Float32\" "
         "NumberOfComponents=\"3\" format=\"ascii\">0 0 0</DataArray></Points></Piece>"
         "</StructuredGrid></VTKFile>"},
    };
    for (const auto& [name, text] : cases) {
        SCOPED_TRACE(name);
        write_file(dir / name, text);
        expect_error(read_mesh(dir / name), dir / name);
    }
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
    const std::size_t at = text.find(from);
    if (at == std::string::npos) throw std::logic_error("test setup: no '" + from + "'");
    return text.replace(at, from.size(), to);
}

// Legacy bodies that VTK 9.1 crashes on or misreads silently (checked with python3-vtk9 on the
// same bytes: a cell count running over its list crashes or corrupts the heap, "CELLSX" is
// CELLS to VTK, ASCII data short of its count is only a warning, OFFSETS under a 4.2 header are
// read as the old layout): each is a one-line error that names the problem.
TEST(BadInput, LegacyBodyCorruptions) {
    test::LegacyLayout ascii;
    test::LegacyLayout binary;
    binary.header = "# vtk DataFile Version 3.0\ntest\nBINARY\n";
    binary.binary = true;
    test::LegacyLayout v51 = ascii;
    v51.header = "# vtk DataFile Version 5.1\ntest\nASCII\n";
    v51.offsets_cells = true;
    test::LegacyLayout new_cells_old_version = v51;
    new_cells_old_version.header = "# vtk DataFile Version 4.2\ntest\nASCII\n";
    test::LegacyLayout old_cells_new_version = ascii;
    old_cells_new_version.header = v51.header;
    const std::string cells = test::legacy_unstructured(ascii);
    std::string binary_cells = test::legacy_unstructured(binary);
    const std::size_t list = binary_cells.find("CELLS 4 27\n") + 11;
    binary_cells.replace(list, 4, std::string("\0\0\x03\xe8", 4));  // first count: 1000
    std::string rectilinear =
        "# vtk DataFile Version 3.0\nr\nASCII\nDATASET RECTILINEAR_GRID\n"
        "DIMENSIONS 2000 2000 2000\n";
    for (const char* axis : {"X", "Y", "Z"}) {
        rectilinear += std::string(axis) + "_COORDINATES 2000 float\n";
        for (int i = 0; i < 2000; ++i) rectilinear += "0 ";
        rectilinear += "\n";
    }
    const std::vector<std::tuple<std::string, std::string, std::string>> cases = {
        {"count_runs_over", replaced(cells, "\n8 0 1 2 3 4 5 6 7 ", "\n100000 0 1 2 3 4 5 6 7 "),
         "cell 0 has 100000 points, but its list has 26 entries left"},
        {"binary_count_runs_over", binary_cells,
         "cell 0 has 1000 points, but its list has 26 entries left"},
        {"fewer_cells_than_declared", replaced(cells, "CELLS 4 27", "CELLS 5 27"),
         "CELLS declares 5 cells, its list holds 4"},
        {"keyword_by_prefix",
         replaced(replaced(cells, "CELLS 4 27", "CELLSX 4 27"), "\n8 0 1", "\n9 0 1"),
         "CELLS: cell 3 has 10 points"},
        {"missing_point_value", replaced(cells, "-1 0 -1 0\n", "-1 0 -1\n"),
         "POINTS: value 36 of 36 is 'CELLS', not a number"},
        {"non_integer_cell", replaced(cells, "\n8 0 1", "\n8 0.5 1"), "not an integer"},
        {"new_cell_layout_old_version", test::legacy_unstructured(new_cells_old_version),
         "the header must say 5.1"},
        {"old_cell_layout_new_version", test::legacy_unstructured(old_cells_new_version),
         "must be followed by OFFSETS"},
        {"offsets_decrease",
         replaced(test::legacy_unstructured(v51), "\n0 8 14 19 23", "\n0 8 4 19 23"),
         "offsets must start at 0, never decrease"},
        {"huge_structured_points",
         replaced(test::legacy_points_grid(ascii), "DIMENSIONS 3 2 2",
                  "DIMENSIONS 100000 100000 100000"),
         "a grid of 1e+15 points is not plausible"},
        {"huge_rectilinear_grid", rectilinear, "a grid of 8e+09 points is not plausible"},
    };
    TempDir dir;
    for (const auto& [name, bytes, message_part] : cases) {
        SCOPED_TRACE(name);
        const fs::path path = dir / (name + ".vtk");
        write_file(path, bytes);
        const std::string message = expect_error(read_mesh(path), path);
        EXPECT_NE(message.find(message_part), std::string::npos) << message;
    }
}

TEST(BadInput, WrongExtension) {
    TempDir dir;
    const fs::path path = dir / "legacy.vtu";
    write_file(path, test::legacy_ascii(test::mixed_mesh(), {}, {}));
    const std::string msg = expect_error(read_mesh(path), path);
    EXPECT_NE(msg.find("legacy"), std::string::npos) << msg;
    // An XML file named .vtk, and a .vtp named .vtu.
    write_file(dir / "xml.vtk", test::vtu_ascii(test::mixed_mesh(), {}, {}));
    expect_error(read_mesh(dir / "xml.vtk"), dir / "xml.vtk");
    std::string vtu = test::vtu_ascii(test::mixed_mesh(), {}, {});
    write_file(dir / "grid.vtp", vtu);
    const std::string msg2 = expect_error(read_mesh(dir / "grid.vtp"), dir / "grid.vtp");
    EXPECT_NE(msg2.find("UnstructuredGrid"), std::string::npos) << msg2;
}

TEST(BadInput, UnknownExtension) {
    TempDir dir;
    const fs::path path = dir / "mesh.foo";
    write_file(path, "whatever");
    auto r = read_mesh(path);
    const std::string msg = expect_error(r, path);
    EXPECT_EQ(r.error().code, ErrorCode::kUnsupported);
    EXPECT_NE(msg.find(".vtu"), std::string::npos) << msg;
    EXPECT_NE(msg.find(".exo"), std::string::npos) << msg;
    write_file(dir / "noext", "whatever");
    expect_error(read_mesh(dir / "noext"), dir / "noext");
    auto s = read_surface(path);
    ASSERT_FALSE(s.ok());
    EXPECT_EQ(s.error().code, ErrorCode::kUnsupported);
    EXPECT_NE(s.error().message.find(".stl"), std::string::npos);
}

TEST(BadInput, NanAndInfCoordinates) {
    TempDir dir;
    for (double bad :
         {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
          -std::numeric_limits<double>::infinity()}) {
        SCOPED_TRACE(bad);
        UnstructuredMesh m = one_tet();
        m.points[2].y = bad;
        const fs::path path = dir / "bad.vtk";
        write_file(path, test::legacy_binary(m));
        auto r = read_mesh(path);
        const std::string msg = expect_error(r, path);
        EXPECT_EQ(r.error().code, ErrorCode::kInvalidMesh);
        EXPECT_NE(msg.find("point 2"), std::string::npos) << msg;
    }
    // Text formats parse "nan" and "inf" and then reject them.
    write_file(dir / "n.node", "2 3 0 0\n1 0 0 0\n2 nan 0 0\n");
    auto node = read_mesh(dir / "n.node");
    EXPECT_NE(expect_error(node, dir / "n.node").find("point 1"), std::string::npos);
    write_file(dir / "i.csv", "x,y,z\n0,0,0\n1,inf,0\n");
    EXPECT_NE(expect_error(read_mesh(dir / "i.csv"), dir / "i.csv").find("point 1"),
              std::string::npos);
    write_file(dir / "n.off", "OFF\n3 1 0\n0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n");
    expect_error(read_surface(dir / "n.off"), dir / "n.off");
}

TEST(BadInput, NanFieldValuesAreKept) {
    TempDir dir;
    const fs::path path = dir / "f.vtk";
    std::string text = test::legacy_ascii(one_tet(), {}, {});
    text += "POINT_DATA 4\nSCALARS s float 1\nLOOKUP_TABLE default\n0 1 nan 3\n";
    write_file(path, text);
    auto r = read_mesh(path);
    // VTK's ASCII parser may or may not accept "nan"; if it does, the value is kept.
    if (r.ok()) {
        const Field* f = find_field(r->point_fields, "s");
        ASSERT_NE(f, nullptr);
        EXPECT_TRUE(std::isnan(f->get(2)));
    } else {
        EXPECT_TRUE(test::one_line(r.error().message));
    }
    write_file(dir / "f.csv", "x,y,z,s\n0,0,0,nan\n");
    auto csv = read_mesh(dir / "f.csv");
    ASSERT_TRUE(csv.ok()) << csv.error().to_string();
    EXPECT_TRUE(std::isnan(csv->point_fields[0].get(0)));
}

TEST(BadInput, OutOfRangeConnectivity) {
    TempDir dir;
    UnstructuredMesh m = one_tet();
    m.connectivity[3] = 99;
    for (const char* name : {"oor.vtk", "oor.vtu"}) {
        SCOPED_TRACE(name);
        const fs::path path = dir / name;
        write_file(path, std::string(name).ends_with(".vtk") ? test::legacy_ascii(m, {}, {})
                                                             : test::vtu_ascii(m, {}, {}));
        auto r = read_mesh(path);
        const std::string msg = expect_error(r, path);
        EXPECT_NE(msg.find("99"), std::string::npos) << msg;
    }
    m.connectivity[3] = -1;
    write_file(dir / "neg.vtu", test::vtu_ascii(m, {}, {}));
    expect_error(read_mesh(dir / "neg.vtu"), dir / "neg.vtu");
    write_file(dir / "t.node", "4 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n");
    write_file(dir / "t.ele", "1 4 0\n1 1 2 3 5\n");
    const std::string msg = expect_error(read_mesh(dir / "t.ele"), dir / "t.ele");
    EXPECT_NE(msg.find("node 5"), std::string::npos) << msg;
    write_file(dir / "o.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n");
    expect_error(read_surface(dir / "o.off"), dir / "o.off");
}

TEST(BadInput, NonMonotoneOffsets) {
    TempDir dir;
    UnstructuredMesh m;
    m.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}};
    m.add_cell(CellType::kTetra, {0, 1, 2, 3});
    m.add_cell(CellType::kTetra, {1, 2, 3, 4});
    m.offsets = {0, 8, 4};
    const fs::path path = dir / "offsets.vtu";
    write_file(path, test::vtu_ascii(m, {}, {}));
    expect_error(read_mesh(path), path);
}

TEST(BadInput, ZeroPointsZeroCells) {
    TempDir dir;
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"empty.vtk",
         "# vtk DataFile Version 3.0\nx\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 0 float\n"
         "CELLS 0 0\nCELL_TYPES 0\n"},
        {"empty.vtu", test::vtu_ascii(UnstructuredMesh{}, {}, {})},
        {"empty.csv", "x,y,z\n"},
        {"empty.node", "0 3 0 0\n"},
    };
    for (const auto& [name, text] : cases) {
        SCOPED_TRACE(name);
        write_file(dir / name, text);
        auto r = read_mesh(dir / name);
        const std::string msg = expect_error(r, dir / name);
        EXPECT_NE(msg.find("empty"), std::string::npos) << msg;
    }
}

TEST(BadInput, TwoDimensionalStructuredGrid) {
    TempDir dir;
    std::string text =
        "# vtk DataFile Version 3.0\nflat\nASCII\nDATASET STRUCTURED_GRID\nDIMENSIONS 3 3 "
        "1\nPOINTS 9 float\n";
    for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i) text += std::to_string(i) + " " + std::to_string(j) + " 0\n";
    write_file(dir / "flat.vtk", text);
    auto r = read_mesh(dir / "flat.vtk");
    const std::string msg = expect_error(r, dir / "flat.vtk");
    EXPECT_NE(msg.find("2-D grid: not a volume"), std::string::npos) << msg;
    write_file(dir / "flat_image.vtk",
               "# vtk DataFile Version 3.0\ni\nASCII\nDATASET STRUCTURED_POINTS\nDIMENSIONS 4 1 4\n"
               "ORIGIN 0 0 0\nSPACING 1 1 1\n");
    const std::string msg2 =
        expect_error(read_mesh(dir / "flat_image.vtk"), dir / "flat_image.vtk");
    EXPECT_NE(msg2.find("2-D grid"), std::string::npos) << msg2;
}

TEST(BadInput, PvdPointsToMissingFile) {
    TempDir dir;
    write_file(
        dir / "s.pvd",
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n<Collection>\n"
        "<DataSet timestep=\"0\" file=\"gone.vtu\"/>\n</Collection>\n</VTKFile>\n");
    auto r = read_mesh(dir / "s.pvd");
    const std::string msg = expect_error(r, dir / "s.pvd");
    EXPECT_EQ(r.error().code, ErrorCode::kNotFound);
    EXPECT_NE(msg.find("gone.vtu"), std::string::npos) << msg;
}

TEST(BadInput, PvtuPieceMissingOrGarbage) {
    TempDir dir;
    const std::string pvtu =
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"PUnstructuredGrid\" version=\"1.0\">\n"
        "<PUnstructuredGrid GhostLevel=\"0\">\n<PPoints><PDataArray type=\"Float64\" "
        "NumberOfComponents=\"3\"/></PPoints>\n<Piece Source=\"piece.vtu\"/>\n"
        "</PUnstructuredGrid>\n</VTKFile>\n";
    write_file(dir / "all.pvtu", pvtu);
    auto missing = read_mesh(dir / "all.pvtu");
    const std::string msg = expect_error(missing, dir / "all.pvtu");
    EXPECT_NE(msg.find("piece.vtu"), std::string::npos) << msg;
    write_file(dir / "piece.vtu", random_bytes(1000, 42));
    expect_error(read_mesh(dir / "all.pvtu"), dir / "piece.vtu");
}

TEST(BadInput, TimeStepOutOfRange) {
    TempDir dir;
    write_file(dir / "a.vtu", test::vtu_ascii(one_tet(), {}, {}));
    write_file(
        dir / "s.pvd",
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n<Collection>\n"
        "<DataSet timestep=\"0\" file=\"a.vtu\"/>\n<DataSet timestep=\"1\" file=\"a.vtu\"/>\n"
        "</Collection>\n</VTKFile>\n");
    for (int step : {2, -1, 1000}) {
        SCOPED_TRACE(step);
        ReadOptions options;
        options.time_step = step;
        auto r = read_mesh(dir / "s.pvd", options);
        expect_error(r, dir / "s.pvd");
        EXPECT_EQ(r.error().code, ErrorCode::kInvalidArgument);
    }
    ReadOptions options;
    options.time_step = 1;
    auto single = read_mesh(dir / "a.vtu", options);
    expect_error(single, dir / "a.vtu");
    EXPECT_EQ(single.error().code, ErrorCode::kInvalidArgument);
    // An Exodus file's steps: io_badinput_realdata_test.cpp.
}

TEST(BadInput, TetgenEleWithoutNode) {
    TempDir dir;
    write_file(dir / "lonely.ele", "1 4 0\n1 1 2 3 4\n");
    auto r = read_mesh(dir / "lonely.ele");
    expect_error(r, dir / "lonely.ele");
    EXPECT_EQ(r.error().code, ErrorCode::kNotFound);
}

TEST(BadInput, TextErrorsNameTheLine) {
    TempDir dir;
    write_file(dir / "bad.csv", "x,y,z\n0,0,0\n1,2,oops\n");
    auto r = read_mesh(dir / "bad.csv");
    expect_error(r, dir / "bad.csv");
    EXPECT_NE(r.error().where.find("bad.csv:3"), std::string::npos) << r.error().where;
}

TEST(BadInput, SurfaceGarbage) {
    TempDir dir;
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"a.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0\n"},
        {"b.stl", std::string(80, 'x') + std::string("\xff\xff\xff\x7f", 4) + "abc"},
        {"c.ply",
         "ply\nformat ascii 1.0\nelement vertex 99999999\nproperty float x\nend_header\n1 2 3\n"},
        {"d.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"},
        {"e.obj", "v 0 0 0\nf 1 2 3\n"},
        {"f.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n"},
        {"g.off", "OFF\n0 0 0\n"},
        {"h.poly", "3 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n1 0\n1\n3 1 2 9\n"},
        {"i.poly", "0 3 0 0\n1 0\n"},
        {"j.off", "COFF\n-5 1 0\n"},
        {"k.vtp", "<VTKFile type=\"PolyData\">" + random_bytes(500, 3) + "</VTKFile>"},
    };
    for (const auto& [name, text] : cases) {
        SCOPED_TRACE(name);
        write_file(dir / name, text);
        expect_error(read_surface(dir / name), dir / name);
    }
}

TEST(BadInput, WriteIntoMissingFolder) {
    TempDir dir;
    auto mesh = TetMesh::create({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, {{0, 1, 2, 3}});
    ASSERT_TRUE(mesh.ok());
    const fs::path path = dir / "missing" / "out.vtu";
    auto st = write_vtu(*mesh, path);
    expect_error(st, path);
    EXPECT_FALSE(fs::exists(path));
    // A path that is a folder.
    auto st2 = write_vtu(*mesh, dir.path());
    EXPECT_FALSE(st2.ok());
}

}  // namespace
}  // namespace tr
