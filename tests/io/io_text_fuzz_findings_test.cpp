// Inputs the text-format fuzz targets (fuzz_surface, fuzz_tetgen, fuzz_csv, fuzz_mfem;
// docs/fuzzing.md) found, and the holes found next to them, each pinned as a file written here:
// read_mesh() / read_surface() must return a one-line error naming the file, never crash.
#include <io/read_mesh.h>
#include <io/read_surface.h>
#include <tests/io/io_test_util.h>

#include <gtest/gtest.h>

#include <string>

namespace tr {
namespace {

using test::expect_error;
using test::TempDir;
using test::write_file;

const std::string kTriangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";

TEST(IoTextFuzzFindings, ObjIndicesOfMissingElementsAreErrors) {
    TempDir dir;
    // Valid faces read (v/vt/vn, v//vn, negative = relative indices; one form per face).
    write_file(dir / "ok.obj",
               kTriangle + "vt 0 0\nvn 0 0 1\nf 1/1/1 2/1/1 -1/-1/-1\nf 1//1 2//1 3//1\n");
    auto ok = read_surface(dir / "ok.obj");
    ASSERT_TRUE(ok.ok()) << ok.error().to_string();
    EXPECT_EQ(ok.value().triangles.size(), 2u);
    // fuzz_surface, smoke run: a face naming texture coordinate 1 in a file without any `vt`
    // made VTK 9.1's OBJ reader dereference null (SIGSEGV in vtkOBJReader::RequestData, exit
    // 139 in a normal build); a normal without `vn`, the same in vtkAOSDataArrayTemplate::
    // GetTuple. Now the OBJ pre-check (measured: "OBJ: 'f' line uses texture coordinate 1 but
    // the file has 0").
    struct Case {
        const char* name;
        std::string text;
        const char* says;
    };
    const Case cases[] = {
        {"no_vt.obj", kTriangle + "f 1/1 2/1 3/1\n", "texture coordinate 1 but the file has 0"},
        {"no_vn.obj", kTriangle + "f 1//1 2//1 3//1\n", "normal 1 but the file has 0"},
        {"vertex.obj", kTriangle + "f 1 2 4\n", "vertex 4 but the file has 3"},
        {"relative.obj", kTriangle + "f -1 -2 -4\n", "vertex -4 but the file has 3 before it"},
        {"zero.obj", kTriangle + "f 0 1 2\n", "vertex 0"},
        {"token.obj", kTriangle + "f 1 2 x\n", "bad index 'x'"},
        {"line.obj", kTriangle + "vt 0 0\nl 1/1/1 2\n", "bad index '1/1/1' in an 'l' line"},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.name);
        write_file(dir / c.name, c.text);
        const std::string message = expect_error(read_surface(dir / c.name), dir / c.name);
        EXPECT_NE(message.find(c.says), std::string::npos) << message;
    }
}

TEST(IoTextFuzzFindings, TetgenIndicesNearInt64LimitsAreErrors) {
    TempDir dir;
    const std::string node = "4 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n";
    write_file(dir / "a.node", node);
    // A node index of -2^63 in a 1-based file: subtracting the base overflowed (undefined
    // behaviour; UBSan: signed integer overflow). Now compared first: "uses node
    // -9223372036854775808, not in the .node file".
    write_file(dir / "a.ele", "1 4 0\n1 1 2 3 -9223372036854775808\n");
    std::string message = expect_error(read_mesh(dir / "a.ele"), dir / "a.ele");
    EXPECT_NE(message.find("uses node -9223372036854775808, not in the .node file"),
              std::string::npos)
        << message;
    // A first tetrahedron index of 2^63 - 1: the next one's expected index overflowed.
    write_file(dir / "a.ele", "2 4 0\n9223372036854775807 1 2 3 4\n-9223372036854775808 1 2 3 4\n");
    message = expect_error(read_mesh(dir / "a.ele"), dir / "a.ele");
    EXPECT_NE(message.find("out of sequence"), std::string::npos) << message;
    // The same subtraction in a .poly's polygon corners.
    write_file(dir / "b.poly", node + "1 0\n1\n3 1 2 -9223372036854775808\n");
    message = expect_error(read_surface(dir / "b.poly"), dir / "b.poly");
    EXPECT_NE(message.find("below the first (1)"), std::string::npos) << message;
}

TEST(IoTextFuzzFindings, TetgenCountsTimesAttributesMustFitTheFile) {
    TempDir dir;
    // A point count and an attribute count each below the file size (what to_count checks)
    // whose product is not: 400 x 400 doubles were allocated before the first point was read
    // (a 1 MB file could ask for terabytes). Now: "400 points of 404 values each cannot fit in
    // a file of 440 bytes".
    std::string node = "400 3 400 0\n";
    node.append(440 - node.size(), '\n');
    write_file(dir / "c.node", node);
    std::string message = expect_error(read_mesh(dir / "c.node"), dir / "c.node");
    EXPECT_NE(message.find("400 points of 404 values each cannot fit in a file of 440 bytes"),
              std::string::npos)
        << message;
    write_file(dir / "d.node", "4 3 0 0\n0 0 0 0\n1 1 0 0\n2 0 1 0\n3 0 0 1\n");
    std::string ele = "100 4 100\n";
    ele.append(300, '\n');
    write_file(dir / "d.ele", ele);
    message = expect_error(read_mesh(dir / "d.ele"), dir / "d.ele");
    EXPECT_NE(message.find("100 tetrahedra of 105 values each cannot fit"), std::string::npos)
        << message;
}

TEST(IoTextFuzzFindings, PolyHoleMustBeFinite) {
    TempDir dir;
    // A .poly hole at NaN was accepted (validate_surface checks points, not holes) and handed to
    // TetGen as a hole point.
    const std::string poly =
        "4 3 0 0\n0 0 0 0\n1 1 0 0\n2 0 1 0\n3 0 0 1\n4 0\n1\n3 0 1 2\n1\n"
        "3 0 1 3\n1\n3 0 2 3\n1\n3 1 2 3\n1\n0 ";
    write_file(dir / "ok.poly", poly + "0.1 0.1 0.1\n");
    auto ok = read_surface(dir / "ok.poly");
    ASSERT_TRUE(ok.ok()) << ok.error().to_string();
    EXPECT_EQ(ok.value().holes.size(), 1u);
    write_file(dir / "nan.poly", poly + "nan 0.1 0.1\n");
    const std::string message = expect_error(read_surface(dir / "nan.poly"), dir / "nan.poly");
    EXPECT_NE(message.find("hole 0 has a non-finite coordinate"), std::string::npos) << message;
}

TEST(IoTextFuzzFindings, MfemRepeatedSectionIsAnError) {
    TempDir dir;
    const std::string head = "MFEM mesh v1.0\ndimension\n3\nelements\n1\n1 4 0 1 2 3\n";
    const std::string vertices = "vertices\n4\n3\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n";
    write_file(dir / "ok.mesh", head + vertices);
    auto ok = read_mesh(dir / "ok.mesh");
    ASSERT_TRUE(ok.ok()) << ok.error().to_string();
    EXPECT_EQ(ok.value().num_cells(), 1u);
    // A second 'elements' section restarted the offsets inside the first one's cells (the
    // error was "offsets has 3 entries for 2 cells"); 'elements 0' after it cleared them.
    write_file(dir / "two.mesh", head + "elements\n1\n1 4 0 1 2 3\n" + vertices);
    std::string message = expect_error(read_mesh(dir / "two.mesh"), dir / "two.mesh");
    EXPECT_NE(message.find("a second 'elements' section"), std::string::npos) << message;
    write_file(dir / "twov.mesh", head + vertices + vertices);
    message = expect_error(read_mesh(dir / "twov.mesh"), dir / "twov.mesh");
    EXPECT_NE(message.find("a second 'vertices' section"), std::string::npos) << message;
}

}  // namespace
}  // namespace tr
