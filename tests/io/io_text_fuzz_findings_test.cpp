// Inputs the file-format fuzz targets (fuzz_surface, fuzz_tetgen, fuzz_csv, fuzz_mfem;
// docs/fuzzing.md) found, and the holes found next to them, each pinned as a file written here:
// read_mesh() / read_surface() must return a one-line error naming the file, never crash.
#include <io/read_mesh.h>
#include <io/read_surface.h>
#include <tests/io/io_test_util.h>

#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <cstdint>
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
        // fuzz_surface, twelfth run: "v0 0" is a vertex to VTK (it reads the command by
        // letters), "f 1/ 1 1" a texture index to it: counts that parted from the check's,
        // and VTK's null dereference again. Keywords, numbers and slashes are checked.
        {"glued.obj", kTriangle + "v0 0\nf 1 2 3\n", "unknown keyword 'v0'"},
        {"short.obj", kTriangle + "v 1 0\nf 1 2 3\n", "'v' needs 3 numbers"},
        {"word.obj", kTriangle + "vn 0 x 1\nf 1 2 3\n", "bad number 'x' in a 'vn' line"},
        {"slash.obj", kTriangle + "f 1/ 2 3\n", "bad index '1/' in an 'f' line"},
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

TEST(IoTextFuzzFindings, PlyAsciiLineShortOfProperties) {
    TempDir dir;
    const std::string head =
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
        "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
    write_file(dir / "ok.ply", head + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
    auto ok = read_surface(dir / "ok.ply");
    ASSERT_TRUE(ok.ok()) << ok.error().to_string();
    EXPECT_EQ(ok.value().triangles.size(), 1u);
    // fuzz_surface, first run: a vertex line with 2 numbers for 3 properties passed the PLY
    // pre-check (it stopped at the last token and found them all used) and VTK's ASCII reader
    // called strtod on the missing third word, a null pointer (SIGSEGV). Now: "malformed PLY
    // vertex 2: '0 1'".
    write_file(dir / "short.ply", head + "0 0 0\n1 0 0\n0 1\n3 0 1 2\n");
    std::string message = expect_error(read_surface(dir / "short.ply"), dir / "short.ply");
    EXPECT_NE(message.find("malformed PLY vertex 2: '0 1'"), std::string::npos) << message;
    // Seventh run: a NUL inside a line ended VTK's words there (a C string), the same read.
    write_file(dir / "nul.ply",
               head + "0 0 0\n1 0 0\n" + std::string("0 1\0 0\n", 7) + "3 0 1 2\n");
    message = expect_error(read_surface(dir / "nul.ply"), dir / "nul.ply");
    EXPECT_NE(message.find("a NUL byte"), std::string::npos) << message;
    // Eleventh run: a word that is not a number ("vertex_index0 1 1") parted VTK's words and
    // ours the same way.
    write_file(dir / "word.ply", head + "0 0 0\n1 0 0\nvertex_index0 1 0\n3 0 1 2\n");
    message = expect_error(read_surface(dir / "word.ply"), dir / "word.ply");
    EXPECT_NE(message.find("'vertex_index0' is not a number"), std::string::npos) << message;
    // Ninth run: bytes beyond ASCII inside a vertex line, the same read (VTK's words differ).
    write_file(dir / "high.ply", head + "0 0 0\n1 0 0\n0 1\xff\xff 0\n3 0 1 2\n");
    message = expect_error(read_surface(dir / "high.ply"), dir / "high.ply");
    EXPECT_NE(message.find("binary data (byte 255) in an ASCII PLY body"), std::string::npos)
        << message;
}

// fuzz_surface, seventeenth run (3.14M executions): an ASCII PLY whose face element has a list
// property besides vertex_indices ('property list uchar int vertex_3') segfaulted VTK 9.1's ASCII
// reader (ascii_get_element), so the pre-check refused it. Our own reader (ply_reader.cpp)
// reads such lists past their values: the triangle is the vertex_indices one.
TEST(IoTextFuzzFindings, PlyAsciiExtraListsAreReadPastTheirValues) {
    TempDir dir;
    const std::string vertices =
        "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n";
    const auto ply = [&](const std::string& face_properties, const std::string& face) {
        return "ply\nformat ascii 1.0\n" + vertices + "element face 1\n" + face_properties +
               "end_header\n0 0 0\n1 0 0\n0 1 0\n" + face + "\n";
    };
    for (const auto& [properties, face] : std::vector<std::pair<std::string, std::string>>{
             {"property list uchar int vertex_indices\n", "3 0 2 1"},
             {"property list uchar int vertex_index\n", "3 0 2 1"},
             {"property list uchar int vertex_indices\nproperty list uchar float texcoord\n",
              "3 0 2 1 6 0 0 1 0 0 1"},
             {"property list uchar int vertex_3\nproperty list uchar int vertex_indices\n",
              "2 1 1 3 0 2 1"},
             {"property list uchar int vertex_indices\nproperty list uchar float vertex_3\n",
              "3 0 2 1 2 0.5 0.5"}}) {
        write_file(dir / "ok.ply", ply(properties, face));
        auto ok = read_surface(dir / "ok.ply");
        ASSERT_TRUE(ok.ok()) << properties << ok.error().to_string();
        ASSERT_EQ(ok.value().triangles.size(), 1u) << properties;
        EXPECT_EQ(ok.value().triangles[0], (std::array<std::uint32_t, 3>{0, 2, 1})) << properties;
    }
    // A list whose length runs past the line is malformed.
    write_file(dir / "long.ply",
               ply("property list uchar int vertex_indices\nproperty list uchar int w\n",
                   "3 0 2 1 5 1 1"));
    const std::string message = expect_error(read_surface(dir / "long.ply"), dir / "long.ply");
    EXPECT_NE(message.find("malformed PLY face 0: '3 0 2 1 5 1 1' (bad list length)"),
              std::string::npos)
        << message;
}

TEST(IoTextFuzzFindings, PlyFaceCornerOutOfRange) {
    TempDir dir;
    // fuzz_surface, second run: a binary PLY whose face list read ASCII text as big-endian ints
    // (corners near 1e9) passed the pre-check, which walked only the sizes, and VTK's reader
    // looked the corners up in the points (SIGSEGV in vtkCell::Initialize). Every corner is now
    // checked, in binary and ASCII files.
    const std::string head =
        "ply\nformat binary_big_endian 1.0\nelement vertex 3\n"
        "property float x\nproperty float y\nproperty float z\n"
        "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
    const auto be32 = [](std::uint32_t v) {
        std::string out(4, '\0');
        for (int b = 0; b < 4; ++b) out[b] = static_cast<char>(v >> (24 - 8 * b));
        return out;
    };
    std::string points;
    for (float c : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f})
        points += be32(std::bit_cast<std::uint32_t>(c));
    write_file(dir / "ok.ply", head + points + '\x03' + be32(0) + be32(1) + be32(2));
    auto ok = read_surface(dir / "ok.ply");
    ASSERT_TRUE(ok.ok()) << ok.error().to_string();
    EXPECT_EQ(ok.value().triangles.size(), 1u);
    write_file(dir / "far.ply", head + points + '\x03' + be32(0) + be32(1) + be32(0x30203020));
    std::string message = expect_error(read_surface(dir / "far.ply"), dir / "far.ply");
    EXPECT_NE(message.find("PLY face 0 uses vertex 807415840, out of range [0, 3)"),
              std::string::npos)
        << message;
    write_file(dir / "next.ply", head + points + '\x03' + be32(0) + be32(1) + be32(3));
    message = expect_error(read_surface(dir / "next.ply"), dir / "next.ply");
    EXPECT_NE(message.find("uses vertex 3, out of range"), std::string::npos) << message;
    const std::string ascii =
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
        "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
        "0 0 0\n1 0 0\n0 1 0\n";
    write_file(dir / "neg.ply", ascii + "3 0 1 -1\n");
    message = expect_error(read_surface(dir / "neg.ply"), dir / "neg.ply");
    EXPECT_NE(message.find("uses vertex -1, out of range"), std::string::npos) << message;
}

TEST(IoTextFuzzFindings, StlIsBinaryByItsSizeElseAscii) {
    TempDir dir;
    const std::string facet =
        "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
        "vertex 0 1 0\nendloop\nendfacet\n";
    write_file(dir / "ok.stl", "solid t\n" + facet + "endsolid t\n");
    auto ok = read_surface(dir / "ok.stl");
    ASSERT_TRUE(ok.ok()) << ok.error().to_string();
    EXPECT_EQ(ok.value().triangles.size(), 1u);
    // A binary STL whose 80-byte header starts with "solid" (as some exporters write it).
    std::string binary = "solid but binary";
    binary.resize(80, ' ');
    const std::uint32_t one = 1;
    binary.append(reinterpret_cast<const char*>(&one), 4);
    const float tri[12] = {0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0};
    binary.append(reinterpret_cast<const char*>(tri), sizeof tri);
    binary.append(2, '\0');
    write_file(dir / "binary.stl", binary);
    ok = read_surface(dir / "binary.stl");
    ASSERT_TRUE(ok.ok()) << ok.error().to_string();
    EXPECT_EQ(ok.value().triangles.size(), 1u);
    // fuzz_surface, third run: a 440-byte file starting "solid" with more than 5% of its first
    // 256 bytes not text was read by VTK as binary, which allocated bytes 80..83's triangle
    // count (libFuzzer: out of memory, over 2 GB). Our reader takes a file as binary only when
    // its size is 84 + 50 n; this one is read as ASCII, and its garbled line named.
    std::string garbled = "solid t\n" + facet;
    garbled.insert(30, std::string(100, '\x9e'));
    garbled += "endsolid t\n";
    write_file(dir / "garbled.stl", garbled);
    const std::string message =
        expect_error(read_surface(dir / "garbled.stl"), dir / "garbled.stl");
    EXPECT_NE(message.find("STL: expected 'outer loop'"), std::string::npos) << message;
}

TEST(IoTextFuzzFindings, PlyElementDeclaredTwice) {
    TempDir dir;
    // fuzz_surface, fourth run: a header with 'element vertex' twice (a line garbled between)
    // made VTK's PLY reader free the first vertex element's storage twice (AddressSanitizer:
    // double-free in vtkPLYReader::RequestData; heap corruption in a normal build).
    const std::string vertex =
        "element vertex 3\nproperty float x\nproperty float y\n"
        "property float z\n";
    const std::string rest =
        "element face 1\nproperty list uchar int vertex_indices\n"
        "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    write_file(dir / "twice.ply", "ply\nformat ascii 1.0\n" + vertex + vertex + rest);
    std::string message = expect_error(read_surface(dir / "twice.ply"), dir / "twice.ply");
    EXPECT_NE(message.find("PLY element 'vertex' declared twice"), std::string::npos) << message;
    write_file(dir / "prop.ply", "ply\nformat ascii 1.0\n" + vertex + "property float z\n" + rest);
    message = expect_error(read_surface(dir / "prop.ply"), dir / "prop.ply");
    EXPECT_NE(message.find("PLY property 'z' declared twice in element 'vertex'"),
              std::string::npos)
        << message;
}

TEST(IoTextFuzzFindings, PlyHeaderEndsAtAnEndHeaderLine) {
    TempDir dir;
    // fuzz_surface, fifth run: the pre-check took the header to end at the first
    // "end_header" anywhere ("end_headeroat y"), VTK at a line whose word is end_header, so
    // VTK read on into the body as header lines and freed garbage in ply_close (ASan: SEGV in
    // free; silent in a normal build, which said "no triangles"). And a face count of "\x16"
    // read as 0. Both are refused now.
    const std::string head =
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
        "property float y\nproperty float z\n";
    const std::string body = "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    write_file(dir / "joined.ply", head +
                                       "element face 1\nproperty list uchar int vertex_indices\n"
                                       "end_headerx\n" +
                                       body);
    std::string message = expect_error(read_surface(dir / "joined.ply"), dir / "joined.ply");
    EXPECT_NE(message.find("unknown PLY header keyword 'end_headerx'"), std::string::npos)
        << message;
    write_file(dir / "count.ply", head +
                                      "element face \x16\nproperty list uchar int "
                                      "vertex_indices\nend_header\n" +
                                      body);
    message = expect_error(read_surface(dir / "count.ply"), dir / "count.ply");
    EXPECT_NE(message.find("binary data (byte 22) in the PLY header"), std::string::npos)
        << message;
    // A count that is text (read as 0 before) is refused as such.
    write_file(dir / "word.ply", head +
                                     "element face x\nproperty list uchar int "
                                     "vertex_indices\nend_header\n" +
                                     body);
    message = expect_error(read_surface(dir / "word.ply"), dir / "word.ply");
    EXPECT_NE(message.find("bad element count"), std::string::npos) << message;
    // Sixth run: "element vertery_big_endian 1.0" (a garbled line) declared an element without
    // properties, whose storage VTK's ply_close freed without having allocated it.
    write_file(dir / "empty.ply", "ply\nformat ascii 1.0\nelement junk 1\n" +
                                      head.substr(std::string("ply\nformat ascii 1.0\n").size()) +
                                      "element face 1\nproperty list uchar int vertex_indices\n"
                                      "end_header\n" +
                                      body);
    message = expect_error(read_surface(dir / "empty.ply"), dir / "empty.ply");
    EXPECT_NE(message.find("PLY element 'junk' has no properties"), std::string::npos) << message;
    // Fifteenth run: an element between the vertices and the faces, which VTK's reader did not
    // skip: it read the faces from that element's data (SIGSEGV in vtkCell::Initialize). Our
    // reader skips it.
    write_file(dir / "between.ply",
               head +
                   "element extra 1\nproperty float w\nelement face 1\n"
                   "property list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n"
                   "0 1 0\n7\n3 0 1 2\n");
    auto between = read_surface(dir / "between.ply");
    ASSERT_TRUE(between.ok()) << between.error().to_string();
    EXPECT_EQ(between.value().triangles.size(), 1u);
    // Eighth run: a header full of OBJ lines (v, vn, f, garbage) made VTK free garbage in
    // ply_close again. Header lines are format, element, property, comment, obj_info only.
    write_file(dir / "obj.ply", "ply\nformat ascii 1.0\nv 0 0 1\n" +
                                    head.substr(std::string("ply\nformat ascii 1.0\n").size()) +
                                    "element face 1\nproperty list uchar int vertex_indices\n"
                                    "end_header\n" +
                                    body);
    message = expect_error(read_surface(dir / "obj.ply"), dir / "obj.ply");
    EXPECT_NE(message.find("unknown PLY header keyword 'v'"), std::string::npos) << message;
    // Tenth run: "property float \fy" was 'y' to the pre-check, not to VTK (SIGSEGV in
    // vtkPLY::find_element). The header must be plain text.
    write_file(dir / "ff.ply",
               "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
               "property float \fy\nproperty float z\nelement face 1\n"
               "property list uchar int vertex_indices\nend_header\n" +
                   body);
    message = expect_error(read_surface(dir / "ff.ply"), dir / "ff.ply");
    EXPECT_NE(message.find("binary data (byte 12) in the PLY header"), std::string::npos)
        << message;
}

// CI of 2026-11-27 (fuzz_surface smoke run) and a 500-second run after it: VTK 9.1's PLY reader
// crashed past every pre-check (SEGV in strlen; in vtkCell::Initialize on a header whose
// 'property list' line ran into the next element's), and its OBJ reader on a file our check
// passed (SEGV in vtkOBJReader::RequestData). PLY, OBJ and STL are now read by our own parsers
// (io/detail/ply_reader.cpp, obj_reader.cpp, stl_reader.cpp): the PLY header is refused naming its
// line, the OBJ reads.
TEST(IoTextFuzzFindings, SurfacesVtkCrashedOnReadByOurParsers) {
    TempDir dir;
    write_file(dir / "crash.ply",
               std::string("ply\nformat binary_big_endian 0.0\ncomment seed\nelement vertex 8\n"
                           "property float x\nproperty float y\nproperty float z\n"
                           "element face 2\nproperty list uchar int vertex_indexvertex_indiement "
                           "face 7\nproperty list uchar int vertex_indices\nend_header\n") +
                   std::string(40, '\0'));
    const std::string message = expect_error(read_surface(dir / "crash.ply"), dir / "crash.ply");
    EXPECT_NE(message.find("malformed PLY property 'property list uchar int "
                           "vertex_indexvertex_indiement face 7'"),
              std::string::npos)
        << message;
    write_file(dir / "crash.obj",
               "# seed\no \xd0\xe2\nv 0  0 1\n\nf 4 1 5#8 1/ 1 0prkper\nv 0 1 0\nv 0 0 1\n"
               "v 1 0 1\nv 1 1  1 5#8\n");
    auto obj = read_surface(dir / "crash.obj");
    ASSERT_TRUE(obj.ok()) << obj.error().to_string();
    ASSERT_EQ(obj->points.size(), 5u);
    ASSERT_EQ(obj->triangles.size(), 1u);
    EXPECT_EQ(obj->triangles[0], (std::array<std::uint32_t, 3>{3, 0, 4}));
    EXPECT_EQ(obj->points[4].z, 1.0);  // "v 1 1  1 5": x y z w, w ignored
}

}  // namespace
}  // namespace tr
