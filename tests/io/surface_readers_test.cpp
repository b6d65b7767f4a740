// Our PLY, OBJ and STL readers (io/detail/ply_reader.cpp, obj_reader.cpp, stl_reader.cpp): one unit
// cube written in every form each format allows (byte orders, value types, element order, extra
// elements and lists, index forms, continued lines, merged STL corners) reads back as the same
// closed surface, with its volume, orientation and corner coordinates exact.

#include <io/read_surface.h>
#include <tests/io/io_test_util.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <string>
#include <vector>

namespace tr {
namespace {

using test::expect_error;
using test::TempDir;
using test::write_file;
namespace fs = std::filesystem;

// The unit cube [0, 1]^3 shifted by 0.25 (coordinates exact in float), its six faces as quads
// wound counter-clockwise seen from outside.
const std::array<std::array<double, 3>, 8> kCorners = {{{0.25, 0.25, 0.25},
                                                        {1.25, 0.25, 0.25},
                                                        {1.25, 1.25, 0.25},
                                                        {0.25, 1.25, 0.25},
                                                        {0.25, 0.25, 1.25},
                                                        {1.25, 0.25, 1.25},
                                                        {1.25, 1.25, 1.25},
                                                        {0.25, 1.25, 1.25}}};
const std::array<std::array<int, 4>, 6> kQuads = {
    {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {2, 3, 7, 6}, {1, 2, 6, 5}, {0, 4, 7, 3}}};

// Each triangle's corners, rotated so the smallest comes first (winding kept), sorted.
std::vector<std::array<std::array<double, 3>, 3>> triangle_set(const SurfaceMesh& s) {
    std::vector<std::array<std::array<double, 3>, 3>> out;
    for (const auto& t : s.triangles) {
        std::array<std::array<double, 3>, 3> tri;
        for (int c = 0; c < 3; ++c) {
            const Vec3& p = s.points[t[static_cast<std::size_t>(c)]];
            tri[static_cast<std::size_t>(c)] = {p.x, p.y, p.z};
        }
        std::rotate(tri.begin(), std::min_element(tri.begin(), tri.end()), tri.end());
        out.push_back(tri);
    }
    std::sort(out.begin(), out.end());
    return out;
}

double enclosed_volume(const SurfaceMesh& s) {
    double v = 0.0;
    for (const auto& t : s.triangles) {
        const Vec3& a = s.points[t[0]];
        const Vec3& b = s.points[t[1]];
        const Vec3& c = s.points[t[2]];
        v += dot(a, cross(b, c)) / 6.0;
    }
    return v;
}

// Fan triangulation of the quads (0, k-1, k), the reference every reader must give.
SurfaceMesh reference_cube() {
    SurfaceMesh s;
    for (const auto& c : kCorners) s.points.emplace_back(c[0], c[1], c[2]);
    for (const auto& q : kQuads) {
        for (int k = 2; k < 4; ++k) {
            s.triangles.push_back({static_cast<std::uint32_t>(q[0]),
                                   static_cast<std::uint32_t>(q[static_cast<std::size_t>(k - 1)]),
                                   static_cast<std::uint32_t>(q[static_cast<std::size_t>(k)])});
        }
    }
    return s;
}

void expect_cube(const fs::path& path, std::size_t points) {
    SCOPED_TRACE(path.filename().string());
    auto s = read_surface(path);
    ASSERT_TRUE(s.ok()) << s.error().to_string();
    EXPECT_EQ(s->points.size(), points);
    EXPECT_EQ(triangle_set(*s), triangle_set(reference_cube()));
    EXPECT_DOUBLE_EQ(enclosed_volume(*s), 1.0);  // closed, outward: the divergence theorem
}

template <class T>
std::string bytes_of(T value, bool big_endian) {
    std::string out(sizeof(T), '\0');
    const auto bits = std::bit_cast<std::array<unsigned char, sizeof(T)>>(value);
    for (std::size_t b = 0; b < sizeof(T); ++b) {
        out[b] = static_cast<char>(big_endian ? bits[sizeof(T) - 1 - b] : bits[b]);
    }
    return out;
}

TEST(SurfaceReaders, PlyAsciiCube) {
    TempDir dir;
    std::string text =
        "ply\nformat ascii 1.0\ncomment a cube\nelement vertex 8\nproperty float x\n"
        "property float y\nproperty float z\nproperty uchar red\n"
        "element face 6\nproperty list uchar int vertex_indices\nend_header\n";
    for (const auto& c : kCorners)
        text +=
            std::to_string(c[0]) + " " + std::to_string(c[1]) + " " + std::to_string(c[2]) + " 7\n";
    for (const auto& q : kQuads) {
        text += "\n4";  // blank lines between instances are skipped
        for (int i : q) text.append(" ").append(std::to_string(i));
    }
    write_file(dir / "cube.ply", text + "\n");
    expect_cube(dir / "cube.ply", 8);
}

// Binary, both byte orders: faces before vertices, an element before both and one after, x a
// double, y and z floats around a uint16, indices as unsigned 32-bit after a list of shorts.
TEST(SurfaceReaders, PlyBinaryCubeInBothByteOrdersAndAnyElementOrder) {
    TempDir dir;
    for (const bool big : {false, true}) {
        std::string data = std::string("ply\nformat ") +
                           (big ? "binary_big_endian" : "binary_little_endian") +
                           " 1.0\nelement material 2\nproperty float shine\n"
                           "element face 6\nproperty list uchar short corner_ids\n"
                           "property list ushort uint vertex_indices\n"
                           "element vertex 8\nproperty double x\nproperty float y\n"
                           "property ushort tag\nproperty float z\n"
                           "element edge 1\nproperty int a\nproperty int b\nend_header\n";
        for (int m = 0; m < 2; ++m) data += bytes_of(0.5f, big);
        for (const auto& q : kQuads) {
            data += '\x02';  // two shorts
            data += bytes_of<std::int16_t>(-1, big);
            data += bytes_of<std::int16_t>(9, big);
            data += bytes_of<std::uint16_t>(4, big);
            for (int i : q) data += bytes_of(static_cast<std::uint32_t>(i), big);
        }
        for (const auto& c : kCorners) {
            data += bytes_of(c[0], big) + bytes_of(static_cast<float>(c[1]), big) +
                    bytes_of<std::uint16_t>(3, big) + bytes_of(static_cast<float>(c[2]), big);
        }
        data += bytes_of<std::int32_t>(0, big) + bytes_of<std::int32_t>(1, big);
        const fs::path path = dir / (big ? "be.ply" : "le.ply");
        write_file(path, data);
        expect_cube(path, 8);
        // One byte short: truncated, named.
        write_file(dir / "short.ply", data.substr(0, data.size() - 1));
        const std::string message =
            expect_error(read_surface(dir / "short.ply"), dir / "short.ply");
        EXPECT_NE(message.find("truncated PLY file: edge 0 of 1"), std::string::npos) << message;
    }
}

// OBJ: texture coordinates and normals in every index form, negative (relative) indices, a face
// continued over two lines, a face naming vertices defined after it, a w coordinate, groups,
// comments.
TEST(SurfaceReaders, ObjCubeInEveryIndexForm) {
    TempDir dir;
    std::string text = "# cube\nmtllib none.mtl\no cube\n";
    for (std::size_t i = 0; i < 4; ++i) {
        const auto& c = kCorners[i];
        text += "v " + std::to_string(c[0]) + " " + std::to_string(c[1]) + " " +
                std::to_string(c[2]) + (i == 0 ? " 1.0" : "") + "\n";
    }
    text += "vt 0 0\nvt 1 0\nvn 0 0 1\ng bottom\ns off\n";
    // Bottom face, relative to the 4 vertices so far: -4 is vertex 1.
    const auto& b = kQuads[0];
    text += "f " + std::to_string(b[0] - 4) + "/-1 " + std::to_string(b[1] - 4) + "/-2 \\\n  " +
            std::to_string(b[2] - 4) + "/-1 " + std::to_string(b[3] - 4) + "/-2  # continued\n";
    // The top face before its vertices (forward references are 1-based absolute).
    const auto& t = kQuads[1];
    text += "f " + std::to_string(t[0] + 1) + "//1 " + std::to_string(t[1] + 1) + "//1 " +
            std::to_string(t[2] + 1) + "//1 " + std::to_string(t[3] + 1) + "//1\n";
    for (std::size_t i = 4; i < 8; ++i) {
        const auto& c = kCorners[i];
        text += "v " + std::to_string(c[0]) + " " + std::to_string(c[1]) + " " +
                std::to_string(c[2]) + "\n";
    }
    text += "usemtl side\n";
    for (std::size_t f = 2; f < 6; ++f) {
        text += "f";
        for (int i : kQuads[f]) text.append(" ").append(std::to_string(i + 1)).append("/1/1");
        text += "\n";
    }
    text += "l 1 2\np 3\n";
    write_file(dir / "cube.obj", text);
    expect_cube(dir / "cube.obj", 8);
}

std::string stl_ascii_facet(const std::array<int, 3>& tri) {
    std::string s = "  facet normal 0 0 0\n    outer loop\n";
    for (int i : tri) {
        const auto& c = kCorners[static_cast<std::size_t>(i)];
        s += "      vertex " + std::to_string(c[0]) + " " + std::to_string(c[1]) + " " +
             std::to_string(c[2]) + "\n";
    }
    return s + "    endloop\n  endfacet\n";
}

// STL lists each triangle's corners on their own: 36 corners merge into the cube's 8 points.
// ASCII in two solids (the last without its endsolid); binary with a header that starts with
// "solid"; a triangle whose corners coincide is dropped.
TEST(SurfaceReaders, StlCubeAsciiAndBinaryMergeTheCorners) {
    TempDir dir;
    const SurfaceMesh cube = reference_cube();
    std::string ascii = "solid first\n";
    for (std::size_t t = 0; t < cube.triangles.size(); ++t) {
        const auto& tri = cube.triangles[t];
        if (t == 6) ascii += "endsolid first\nsolid second\n";
        ascii += stl_ascii_facet(
            {static_cast<int>(tri[0]), static_cast<int>(tri[1]), static_cast<int>(tri[2])});
    }
    ascii += stl_ascii_facet({0, 0, 1});  // degenerate once merged
    write_file(dir / "cube.stl", ascii);
    expect_cube(dir / "cube.stl", 8);

    std::string binary = "solid but binary";
    binary.resize(80, ' ');
    binary += bytes_of<std::uint32_t>(static_cast<std::uint32_t>(cube.triangles.size()), false);
    for (const auto& tri : cube.triangles) {
        for (int k = 0; k < 3; ++k) binary += bytes_of(0.0f, false);  // the normal
        for (std::uint32_t i : tri) {
            for (double x : kCorners[i]) binary += bytes_of(static_cast<float>(x), false);
        }
        binary += std::string(2, '\0');
    }
    write_file(dir / "binary.stl", binary);
    expect_cube(dir / "binary.stl", 8);

    // Cut inside a facet: truncated, not a smaller cube.
    write_file(dir / "cut.stl", ascii.substr(0, ascii.rfind("endloop")));
    const std::string message = expect_error(read_surface(dir / "cut.stl"), dir / "cut.stl");
    EXPECT_NE(message.find("truncated STL file: it ends inside a facet"), std::string::npos)
        << message;
}

}  // namespace
}  // namespace tr
