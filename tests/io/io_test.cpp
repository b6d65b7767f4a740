// Format round trips for io/: hand-written files in every format read_mesh()/read_surface()
// accept, read back and compared; write_vtu() then read_mesh().

#include <io/read_mesh.h>
#include <io/read_surface.h>
#include <io/write_vtu.h>
#include <mesh/tet_mesh.h>
#include <tests/io/io_test_util.h>

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

namespace tr {
namespace {

namespace fs = std::filesystem;

using test::TempDir;
using test::TestArray;
using test::write_file;

constexpr double kMixedVolume = 1.0 + 0.5 + 1.0 / 3.0 + 1.0 / 6.0;

void expect_same_cells(const UnstructuredMesh& a, const UnstructuredMesh& b) {
    ASSERT_EQ(a.num_points(), b.num_points());
    for (std::size_t i = 0; i < a.num_points(); ++i) {
        EXPECT_DOUBLE_EQ(a.points[i].x, b.points[i].x) << "point " << i;
        EXPECT_DOUBLE_EQ(a.points[i].y, b.points[i].y) << "point " << i;
        EXPECT_DOUBLE_EQ(a.points[i].z, b.points[i].z) << "point " << i;
    }
    EXPECT_EQ(a.types, b.types);
    EXPECT_EQ(a.offsets, b.offsets);
    EXPECT_EQ(a.connectivity, b.connectivity);
}

const Field& field(const std::vector<Field>& fields, const std::string& name) {
    const Field* f = find_field(fields, name);
    if (f == nullptr) throw std::runtime_error("no field " + name);
    return *f;
}

std::vector<TestArray> mixed_point_arrays() {
    std::vector<double> f32, vec, ints;
    for (int i = 0; i < 12; ++i) {
        f32.push_back(0.5 * i);
        vec.insert(vec.end(), {1.0 * i, 2.0 * i, 3.0 * i});
        ints.push_back(100 + i);
    }
    return {{"temperature", "Float32", 1, f32},
            {"velocity", "Float64", 3, vec},
            {"id", "Int32", 1, ints}};
}

std::vector<TestArray> mixed_cell_arrays() {
    return {{"pressure", "Float64", 1, {1.5, 2.5, 3.5, 4.5}}, {"region", "Int32", 1, {1, 2, 3, 4}}};
}

void expect_mixed_arrays(const UnstructuredMesh& mesh) {
    const Field& t = field(mesh.point_fields, "temperature");
    EXPECT_FALSE(t.is_double()) << "float32 must stay float32";
    EXPECT_EQ(t.num_components, 1);
    EXPECT_FLOAT_EQ(static_cast<float>(t.get(3)), 1.5f);
    const Field& v = field(mesh.point_fields, "velocity");
    EXPECT_TRUE(v.is_double());
    EXPECT_EQ(v.num_components, 3);
    EXPECT_DOUBLE_EQ(v.get(4, 2), 12.0);
    const Field& id = field(mesh.point_fields, "id");
    EXPECT_TRUE(id.is_double()) << "integer arrays become float64";
    EXPECT_DOUBLE_EQ(id.get(11), 111.0);
    const Field& p = field(mesh.cell_fields, "pressure");
    EXPECT_TRUE(p.is_double());
    EXPECT_DOUBLE_EQ(p.get(2), 3.5);
    EXPECT_DOUBLE_EQ(field(mesh.cell_fields, "region").get(3), 4.0);
}

TEST(ReadMesh, VtuAsciiMixedCellsAndArrays) {
    TempDir dir;
    const UnstructuredMesh in = test::mixed_mesh();
    write_file(dir / "mixed.vtu", test::vtu_ascii(in, mixed_point_arrays(), mixed_cell_arrays()));
    auto mesh = read_mesh(dir / "mixed.vtu");
    ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
    expect_same_cells(in, *mesh);
    expect_mixed_arrays(*mesh);
    EXPECT_EQ(mesh->format, "VTK XML unstructured grid");
    EXPECT_TRUE(mesh->time_values.empty());
    EXPECT_NEAR(test::total_abs_volume(*mesh), kMixedVolume, 1e-12);
    for (std::size_t c = 0; c < mesh->num_cells(); ++c) {
        EXPECT_GT(test::cell_volume(*mesh, c), 0.0) << "cell " << c;
    }
}

TEST(ReadMesh, ExtensionIsCaseInsensitive) {
    TempDir dir;
    write_file(dir / "MIXED.VTU", test::vtu_ascii(test::mixed_mesh(), {}, {}));
    auto mesh = read_mesh(dir / "MIXED.VTU");
    ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
    EXPECT_EQ(mesh->num_cells(), 4u);
}

TEST(ReadMesh, LegacyAsciiUnstructuredGrid) {
    TempDir dir;
    const UnstructuredMesh in = test::mixed_mesh();
    write_file(dir / "mixed.vtk",
               test::legacy_ascii(in, mixed_point_arrays(), mixed_cell_arrays()));
    auto mesh = read_mesh(dir / "mixed.vtk");
    ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
    expect_same_cells(in, *mesh);
    expect_mixed_arrays(*mesh);
    EXPECT_EQ(mesh->format, "VTK legacy unstructured grid");
}

TEST(ReadMesh, LegacyBinaryUnstructuredGrid) {
    TempDir dir;
    const UnstructuredMesh in = test::mixed_mesh();
    write_file(dir / "mixed.vtk", test::legacy_binary(in));
    auto mesh = read_mesh(dir / "mixed.vtk");
    ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
    expect_same_cells(in, *mesh);  // coordinates are exact in float32
}

// A 3 x 4 x 2 grid of points on a sheared box: 2 * 3 * 1 = 6 hexahedra.
std::string structured_points_text(bool with_points) {
    std::ostringstream out;
    if (with_points) {
        out << "POINTS 24 float\n";
        for (int k = 0; k < 2; ++k) {
            for (int j = 0; j < 4; ++j) {
                for (int i = 0; i < 3; ++i)
                    out << i + 0.25 * k << " " << 2 * j << " " << 3 * k << "\n";
            }
        }
    }
    return out.str();
}

TEST(ReadMesh, LegacyStructuredGridBecomesHexahedra) {
    TempDir dir;
    std::string text =
        "# vtk DataFile Version 3.0\ngrid\nASCII\nDATASET STRUCTURED_GRID\nDIMENSIONS 3 4 2\n";
    text += structured_points_text(true);
    text += "POINT_DATA 24\nSCALARS s float 1\nLOOKUP_TABLE default\n";
    for (int i = 0; i < 24; ++i) text += std::to_string(i) + "\n";
    text += "CELL_DATA 6\nSCALARS c double 1\nLOOKUP_TABLE default\n0 1 2 3 4 5\n";
    write_file(dir / "grid.vtk", text);
    auto mesh = read_mesh(dir / "grid.vtk");
    ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
    EXPECT_EQ(mesh->num_points(), 24u);
    ASSERT_EQ(mesh->num_cells(), 6u);
    for (CellType t : mesh->types) EXPECT_EQ(t, CellType::kHexahedron);
    // Cell 0 is (i, j, k) = (0, 0, 0): points 0, 1, 4, 3, 12, 13, 16, 15.
    const std::vector<std::int64_t> first(mesh->connectivity.begin(),
                                          mesh->connectivity.begin() + 8);
    EXPECT_EQ(first, (std::vector<std::int64_t>{0, 1, 4, 3, 12, 13, 16, 15}));
    // Volume of the sheared box 2 x 6 x 3 = 36, whatever the grid's handedness.
    EXPECT_NEAR(test::total_abs_volume(*mesh), 36.0, 1e-9);
    EXPECT_FALSE(field(mesh->point_fields, "s").is_double());
    EXPECT_DOUBLE_EQ(field(mesh->cell_fields, "c").get(5), 5.0);
    EXPECT_EQ(mesh->format, "VTK legacy structured grid");
}

TEST(ReadMesh, LegacyRectilinearGridAndStructuredPoints) {
    TempDir dir;
    write_file(dir / "rect.vtk",
               "# vtk DataFile Version 3.0\nr\nASCII\nDATASET RECTILINEAR_GRID\nDIMENSIONS 2 3 4\n"
               "X_COORDINATES 2 float\n0 1\nY_COORDINATES 3 float\n0 1 3\n"
               "Z_COORDINATES 4 float\n0 1 2 4\n");
    auto rect = read_mesh(dir / "rect.vtk");
    ASSERT_TRUE(rect.ok()) << rect.error().to_string();
    EXPECT_EQ(rect->num_points(), 24u);
    EXPECT_EQ(rect->num_cells(), 6u);
    EXPECT_NEAR(test::total_abs_volume(*rect), 1.0 * 3.0 * 4.0, 1e-12);

    write_file(dir / "image.vtk",
               "# vtk DataFile Version 3.0\ni\nASCII\nDATASET STRUCTURED_POINTS\nDIMENSIONS 3 3 3\n"
               "ORIGIN 1 2 3\nSPACING 0.5 0.5 2\n");
    auto image = read_mesh(dir / "image.vtk");
    ASSERT_TRUE(image.ok()) << image.error().to_string();
    EXPECT_EQ(image->num_points(), 27u);
    EXPECT_EQ(image->num_cells(), 8u);
    EXPECT_NEAR(test::total_abs_volume(*image), 1.0 * 1.0 * 4.0, 1e-12);
    EXPECT_DOUBLE_EQ(image->points[26].z, 7.0);
}

TEST(ReadMesh, LegacyPolydataVerticesIsPointCloud) {
    TempDir dir;
    write_file(dir / "cloud.vtk",
               "# vtk DataFile Version 3.0\nc\nASCII\nDATASET POLYDATA\nPOINTS 3 float\n"
               "0 0 0 1 0 0 0 1 0\nVERTICES 3 6\n1 0\n1 1\n1 2\n"
               "POINT_DATA 3\nSCALARS s double 1\nLOOKUP_TABLE default\n1 2 3\n");
    auto mesh = read_mesh(dir / "cloud.vtk");
    ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
    EXPECT_TRUE(mesh->is_point_cloud());
    EXPECT_EQ(mesh->num_points(), 3u);
    EXPECT_DOUBLE_EQ(field(mesh->point_fields, "s").get(2), 3.0);
}

TEST(ReadMesh, PolydataWithPolygonsIsAnError) {
    TempDir dir;
    write_file(dir / "tri.vtk",
               "# vtk DataFile Version 3.0\nc\nASCII\nDATASET POLYDATA\nPOINTS 3 float\n"
               "0 0 0 1 0 0 0 1 0\nPOLYGONS 1 4\n3 0 1 2\n");
    auto mesh = read_mesh(dir / "tri.vtk");
    ASSERT_FALSE(mesh.ok());
    EXPECT_NE(mesh.error().message.find("surface"), std::string::npos) << mesh.error().message;
    // ... and read_surface takes it.
    auto surface = read_surface(dir / "tri.vtk");
    ASSERT_TRUE(surface.ok()) << surface.error().to_string();
    EXPECT_EQ(surface->triangles.size(), 1u);
}

std::string xml_structured(const std::string& type, const std::string& extent,
                           const std::string& piece_extra, const std::string& body) {
    return "<?xml version=\"1.0\"?>\n<VTKFile type=\"" + type +
           "\" version=\"1.0\" byte_order=\"LittleEndian\">\n  <" + type + " WholeExtent=\"" +
           extent + "\"" + piece_extra + ">\n    <Piece Extent=\"" + extent + "\">\n" + body +
           "    </Piece>\n  </" + type + ">\n</VTKFile>\n";
}

TEST(ReadMesh, XmlStructuredRectilinearImage) {
    TempDir dir;
    std::string pts =
        "      <Points><DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"ascii\">\n";
    for (int k = 0; k < 2; ++k)
        for (int j = 0; j < 2; ++j)
            for (int i = 0; i < 3; ++i)
                pts += std::to_string(i) + " " + std::to_string(j) + " " + std::to_string(k) + "\n";
    pts += "      </DataArray></Points>\n";
    pts +=
        "      <PointData><DataArray type=\"Float32\" Name=\"f\" format=\"ascii\">0 1 2 3 4 5 6 7 "
        "8 9 10 11</DataArray></PointData>\n";
    write_file(dir / "g.vts", xml_structured("StructuredGrid", "0 2 0 1 0 1", "", pts));
    auto vts = read_mesh(dir / "g.vts");
    ASSERT_TRUE(vts.ok()) << vts.error().to_string();
    EXPECT_EQ(vts->num_cells(), 2u);
    EXPECT_NEAR(test::total_abs_volume(*vts), 2.0, 1e-12);
    EXPECT_FALSE(field(vts->point_fields, "f").is_double());

    const std::string coords =
        "      <Coordinates>\n"
        "        <DataArray type=\"Float64\" format=\"ascii\">0 1 3</DataArray>\n"
        "        <DataArray type=\"Float64\" format=\"ascii\">0 2</DataArray>\n"
        "        <DataArray type=\"Float64\" format=\"ascii\">0 5</DataArray>\n"
        "      </Coordinates>\n";
    write_file(dir / "r.vtr", xml_structured("RectilinearGrid", "0 2 0 1 0 1", "", coords));
    auto vtr = read_mesh(dir / "r.vtr");
    ASSERT_TRUE(vtr.ok()) << vtr.error().to_string();
    EXPECT_EQ(vtr->num_cells(), 2u);
    EXPECT_NEAR(test::total_abs_volume(*vtr), 3.0 * 2.0 * 5.0, 1e-12);

    write_file(dir / "i.vti",
               xml_structured("ImageData", "0 2 0 2 0 2", " Origin=\"0 0 0\" Spacing=\"1 1 1\"",
                              "      <CellData><DataArray type=\"Float64\" Name=\"c\" "
                              "format=\"ascii\">1 2 3 4 5 6 7 8</DataArray></CellData>\n"));
    auto vti = read_mesh(dir / "i.vti");
    ASSERT_TRUE(vti.ok()) << vti.error().to_string();
    EXPECT_EQ(vti->num_cells(), 8u);
    EXPECT_NEAR(test::total_abs_volume(*vti), 8.0, 1e-12);
    EXPECT_DOUBLE_EQ(field(vti->cell_fields, "c").get(7), 8.0);
}

std::string vtp(const std::string& cells) {
    return "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"1.0\" "
           "byte_order=\"LittleEndian\">\n"
           "  <PolyData>\n    <Piece NumberOfPoints=\"4\" NumberOfVerts=\"0\" NumberOfLines=\"0\" "
           "NumberOfStrips=\"0\" NumberOfPolys=\"" +
           std::string(cells.empty() ? "0" : "1") +
           "\">\n"
           "      <PointData><DataArray type=\"Float32\" Name=\"w\" format=\"ascii\">1 2 3 "
           "4</DataArray></PointData>\n"
           "      <Points><DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"ascii\">"
           "0 0 0 1 0 0 1 1 0 0 1 0</DataArray></Points>\n" +
           cells + "    </Piece>\n  </PolyData>\n</VTKFile>\n";
}

TEST(ReadMesh, VtpPointsArePointCloudAndPolygonsAreSurface) {
    TempDir dir;
    write_file(dir / "cloud.vtp", vtp(""));
    auto cloud = read_mesh(dir / "cloud.vtp");
    ASSERT_TRUE(cloud.ok()) << cloud.error().to_string();
    EXPECT_TRUE(cloud->is_point_cloud());
    EXPECT_EQ(cloud->num_points(), 4u);
    EXPECT_FALSE(field(cloud->point_fields, "w").is_double());

    write_file(
        dir / "quad.vtp",
        vtp("      <Polys><DataArray type=\"Int32\" Name=\"connectivity\" format=\"ascii\">0 1 2 "
            "3</DataArray>"
            "<DataArray type=\"Int32\" Name=\"offsets\" format=\"ascii\">4</DataArray></Polys>\n"));
    auto as_mesh = read_mesh(dir / "quad.vtp");
    ASSERT_FALSE(as_mesh.ok());
    EXPECT_NE(as_mesh.error().message.find("surface"), std::string::npos);
    auto surface = read_surface(dir / "quad.vtp");
    ASSERT_TRUE(surface.ok()) << surface.error().to_string();
    EXPECT_EQ(surface->triangles.size(), 2u);
    EXPECT_EQ(surface->name, "quad");
}

TEST(ReadMesh, PvtuJoinsPieces) {
    TempDir dir;
    UnstructuredMesh a;
    a.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    a.add_cell(CellType::kTetra, {0, 1, 2, 3});
    UnstructuredMesh b = a;
    for (Vec3& p : b.points) p.x += 5;
    write_file(dir / "p0.vtu", test::vtu_ascii(a, {{"f", "Float32", 1, {1, 2, 3, 4}}}, {}));
    write_file(dir / "p1.vtu", test::vtu_ascii(b, {{"f", "Float32", 1, {5, 6, 7, 8}}}, {}));
    write_file(dir / "all.pvtu",
               "<?xml version=\"1.0\"?>\n<VTKFile type=\"PUnstructuredGrid\" version=\"1.0\" "
               "byte_order=\"LittleEndian\" header_type=\"UInt64\">\n  <PUnstructuredGrid "
               "GhostLevel=\"0\">\n"
               "    <PPointData><PDataArray type=\"Float32\" Name=\"f\"/></PPointData>\n"
               "    <PPoints><PDataArray type=\"Float64\" NumberOfComponents=\"3\"/></PPoints>\n"
               "    <Piece Source=\"p0.vtu\"/>\n    <Piece Source=\"p1.vtu\"/>\n"
               "  </PUnstructuredGrid>\n</VTKFile>\n");
    auto mesh = read_mesh(dir / "all.pvtu");
    ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
    EXPECT_EQ(mesh->num_points(), 8u);
    EXPECT_EQ(mesh->num_cells(), 2u);
    EXPECT_DOUBLE_EQ(field(mesh->point_fields, "f").get(7), 8.0);
    EXPECT_NEAR(test::total_abs_volume(*mesh), 2.0 / 6.0, 1e-12);
}

std::string pvd(const std::vector<std::pair<double, std::string>>& steps) {
    std::string text =
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n  <Collection>\n";
    for (const auto& [t, file] : steps) {
        std::ostringstream line;
        line << "    <DataSet timestep=\"" << t << "\" part=\"0\" file=\"" << file << "\"/>\n";
        text += line.str();
    }
    return text + "  </Collection>\n</VTKFile>\n";
}

TEST(ReadMesh, PvdTimeSeries) {
    TempDir dir;
    fs::create_directories(dir / "steps");
    UnstructuredMesh m = test::mixed_mesh();
    write_file(dir / "steps" / "s0.vtu",
               test::vtu_ascii(m, {}, {{"t", "Float64", 1, {0, 0, 0, 0}}}));
    for (Vec3& p : m.points) p *= 2.0;
    write_file(dir / "steps" / "s1.vtu",
               test::vtu_ascii(m, {}, {{"t", "Float64", 1, {1, 1, 1, 1}}}));
    // Listed out of order: the steps are sorted by time.
    write_file(dir / "series.pvd", pvd({{0.5, "steps/s1.vtu"}, {0.25, "steps/s0.vtu"}}));

    std::vector<double> fractions;
    ReadOptions options;
    options.progress = [&](std::string_view stage, double f) {
        EXPECT_EQ(stage, "reading");
        fractions.push_back(f);
    };
    auto first = read_mesh(dir / "series.pvd", options);
    ASSERT_TRUE(first.ok()) << first.error().to_string();
    EXPECT_EQ(first->time_values, (std::vector<double>{0.25, 0.5}));
    EXPECT_EQ(first->time_step, 0);
    EXPECT_DOUBLE_EQ(field(first->cell_fields, "t").get(0), 0.0);
    EXPECT_NEAR(test::total_abs_volume(*first), kMixedVolume, 1e-12);
    ASSERT_GE(fractions.size(), 2u);
    EXPECT_EQ(fractions.front(), 0.0);
    EXPECT_EQ(fractions.back(), 1.0);
    EXPECT_TRUE(std::is_sorted(fractions.begin(), fractions.end()));

    options.time_step = 1;
    auto second = read_mesh(dir / "series.pvd", options);
    ASSERT_TRUE(second.ok()) << second.error().to_string();
    EXPECT_EQ(second->time_step, 1);
    EXPECT_DOUBLE_EQ(field(second->cell_fields, "t").get(0), 1.0);
    EXPECT_NEAR(test::total_abs_volume(*second), 8 * kMixedVolume, 1e-9);
    EXPECT_NE(second->format.find(".pvd"), std::string::npos);
}

TEST(ReadMesh, ProgressReportsZeroAndOne) {
    TempDir dir;
    write_file(dir / "m.vtk", test::legacy_ascii(test::mixed_mesh(), {}, {}));
    std::vector<double> fractions;
    ReadOptions options;
    options.progress = [&](std::string_view, double f) { fractions.push_back(f); };
    auto mesh = read_mesh(dir / "m.vtk", options);
    ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
    ASSERT_GE(fractions.size(), 2u);
    EXPECT_EQ(fractions.front(), 0.0);
    EXPECT_EQ(fractions.back(), 1.0);
    for (double f : fractions) {
        EXPECT_GE(f, 0.0);
        EXPECT_LE(f, 1.0);
    }
}

TEST(ReadMesh, TetgenOneBasedWithAttributes) {
    TempDir dir;
    write_file(dir / "m.node",
               "# points\n5 3 2 1\n1 0 0 0 10 -1 1\n2 1 0 0 11 -2 1\n3 0 1 0 12 -3 0\n"
               "4 0 0 1 13 -4 0\n5 1 1 1 14 -5 0\n");
    write_file(dir / "m.ele", "2 4 1\n1 1 2 3 4 7\n2 2 3 4 5 8  # second\n");
    for (const char* name : {"m.node", "m.ele"}) {
        SCOPED_TRACE(name);
        auto mesh = read_mesh(dir / name);
        ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
        EXPECT_EQ(mesh->num_points(), 5u);
        ASSERT_EQ(mesh->num_cells(), 2u);
        EXPECT_EQ(mesh->types[0], CellType::kTetra);
        EXPECT_EQ(mesh->connectivity, (std::vector<std::int64_t>{0, 1, 2, 3, 1, 2, 3, 4}));
        EXPECT_DOUBLE_EQ(field(mesh->point_fields, "attr0").get(4), 14.0);
        EXPECT_DOUBLE_EQ(field(mesh->point_fields, "attr1").get(1), -2.0);
        EXPECT_DOUBLE_EQ(field(mesh->cell_fields, "attr0").get(1), 8.0);
    }
}

TEST(ReadMesh, TetgenZeroBasedAndNodeOnlyIsPointCloud) {
    TempDir dir;
    write_file(dir / "z.node", "4 3 0 0\n0 0 0 0\n1 1 0 0\n2 0 1 0\n3 0 0 1\n");
    auto cloud = read_mesh(dir / "z.node");
    ASSERT_TRUE(cloud.ok()) << cloud.error().to_string();
    EXPECT_TRUE(cloud->is_point_cloud());
    write_file(dir / "z.ele", "1 4 0\n0 0 1 2 3\n");
    auto mesh = read_mesh(dir / "z.ele");
    ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
    EXPECT_EQ(mesh->connectivity, (std::vector<std::int64_t>{0, 1, 2, 3}));
    EXPECT_NEAR(test::total_abs_volume(*mesh), 1.0 / 6.0, 1e-15);
}

TEST(ReadMesh, CsvPointCloud) {
    TempDir dir;
    write_file(dir / "p.csv",
               "x,y,z,density,\"speed\"\n0,0,0,1.5,2\n1,2,3,2.5,3\r\n\n-1e-3,4,5,3.5,4\n");
    auto mesh = read_mesh(dir / "p.csv");
    ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
    EXPECT_TRUE(mesh->is_point_cloud());
    ASSERT_EQ(mesh->num_points(), 3u);
    EXPECT_DOUBLE_EQ(mesh->points[2].x, -1e-3);
    EXPECT_DOUBLE_EQ(field(mesh->point_fields, "density").get(1), 2.5);
    EXPECT_DOUBLE_EQ(field(mesh->point_fields, "speed").get(2), 4.0);
    EXPECT_EQ(mesh->format, "CSV point cloud");
}

TEST(ReadMesh, MfemMixedElements) {
    TempDir dir;
    // A unit cube (hex), a prism on its +x side and a tet and a pyramid, MFEM numbering.
    write_file(dir / "m.mesh",
               "MFEM mesh v1.0\n\n# comment\ndimension\n3\n\nelements\n4\n"
               "1 5 0 1 2 3 4 5 6 7\n"
               "2 6 1 8 2 5 9 6\n"
               "3 4 0 1 4 11\n"
               "4 7 0 3 2 1 10\n"
               "\nboundary\n1\n1 3 0 1 2 3\n\nvertices\n12\n3\n"
               "0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n2 0 0\n2 0 1\n0.5 0.5 "
               "-1\n0 -1 0\n");
    auto mesh = read_mesh(dir / "m.mesh");
    ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
    ASSERT_EQ(mesh->num_cells(), 4u);
    EXPECT_EQ(mesh->types, (std::vector<CellType>{CellType::kHexahedron, CellType::kWedge,
                                                  CellType::kTetra, CellType::kPyramid}));
    // MFEM prism (1 8 2 5 9 6) -> VTK wedge (1 2 8 5 6 9): positive VTK volume.
    EXPECT_EQ(
        std::vector<std::int64_t>(mesh->connectivity.begin() + 8, mesh->connectivity.begin() + 14),
        (std::vector<std::int64_t>{1, 2, 8, 5, 6, 9}));
    for (std::size_t c = 0; c < 4; ++c) EXPECT_GT(test::cell_volume(*mesh, c), 0.0) << "cell " << c;
    EXPECT_NEAR(test::total_abs_volume(*mesh), kMixedVolume, 1e-12);
    EXPECT_DOUBLE_EQ(field(mesh->cell_fields, "attribute").get(3), 4.0);
}

TEST(ReadMesh, SupportedExtensions) {
    const std::vector<std::string> exts = supported_mesh_extensions();
    for (const char* e : {".vtu", ".pvtu", ".vtk", ".vts", ".vtr", ".vti", ".vtp", ".exo", ".e",
                          ".ex2", ".g", ".exii", ".pvd", ".node", ".ele", ".csv", ".mesh"}) {
        EXPECT_NE(std::find(exts.begin(), exts.end(), e), exts.end()) << e;
    }
}

// ------------------------------------------------------------------------------------------
// Surfaces

TEST(ReadSurface, OffFanTriangulates) {
    TempDir dir;
    write_file(dir / "box.off",
               "OFF\n# a quad and a triangle\n5 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n4 0 1 2 "
               "3\n3 0 1 4 255 0 0\n");
    auto s = read_surface(dir / "box.off");
    ASSERT_TRUE(s.ok()) << s.error().to_string();
    EXPECT_EQ(s->points.size(), 5u);
    ASSERT_EQ(s->triangles.size(), 3u);
    EXPECT_EQ(s->triangles[1], (std::array<std::uint32_t, 3>{0, 2, 3}));
    EXPECT_EQ(s->name, "box");
}

TEST(ReadSurface, TetgenPolyWithHoles) {
    TempDir dir;
    write_file(
        dir / "cube.poly",
        "# part 1\n8 3 0 0\n1 0 0 0\n2 1 0 0\n3 1 1 0\n4 0 1 0\n5 0 0 1\n6 1 0 1\n7 1 1 1\n8 0 1 "
        "1\n"
        "# part 2\n6 1\n1 0 1\n4 1 2 3 4\n1 0 1\n4 5 6 7 8\n1 0 1\n4 1 2 6 5\n1 0 1\n4 2 3 7 6\n"
        "1 0 1\n4 3 4 8 7\n1 0 1\n4 4 1 5 8\n# part 3\n1\n1 0.5 0.5 0.5\n# part 4\n0\n");
    auto s = read_surface(dir / "cube.poly");
    ASSERT_TRUE(s.ok()) << s.error().to_string();
    EXPECT_EQ(s->points.size(), 8u);
    EXPECT_EQ(s->triangles.size(), 12u);
    ASSERT_EQ(s->holes.size(), 1u);
    EXPECT_DOUBLE_EQ(s->holes[0].y, 0.5);
    EXPECT_EQ(s->triangles[0], (std::array<std::uint32_t, 3>{0, 1, 2}));
}

TEST(ReadSurface, AsciiStlObjPly) {
    TempDir dir;
    write_file(dir / "t.stl",
               "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 "
               "0\nendloop\nendfacet\n"
               "facet normal 0 0 1\nouter loop\nvertex 1 0 0\nvertex 1 1 0\nvertex 0 1 "
               "0\nendloop\nendfacet\nendsolid t\n");
    auto stl = read_surface(dir / "t.stl");
    ASSERT_TRUE(stl.ok()) << stl.error().to_string();
    EXPECT_EQ(stl->triangles.size(), 2u);
    EXPECT_EQ(stl->points.size(), 4u);  // merged

    write_file(dir / "q.obj", "# quad\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n");
    auto obj = read_surface(dir / "q.obj");
    ASSERT_TRUE(obj.ok()) << obj.error().to_string();
    EXPECT_EQ(obj->triangles.size(), 2u);

    write_file(dir / "t.ply",
               "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float "
               "y\nproperty float z\n"
               "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 "
               "0\n0 1 0\n3 0 1 2\n");
    auto ply = read_surface(dir / "t.ply");
    ASSERT_TRUE(ply.ok()) << ply.error().to_string();
    EXPECT_EQ(ply->triangles.size(), 1u);
    EXPECT_EQ(ply->points.size(), 3u);
}

TEST(ReadSurface, BinaryStl) {
    TempDir dir;
    std::string bytes(80, ' ');
    const std::uint32_t n = 1;
    bytes.append(reinterpret_cast<const char*>(&n), 4);
    const float tri[12] = {0, 0, 1, 0, 0, 0, 2, 0, 0, 0, 2, 0};
    bytes.append(reinterpret_cast<const char*>(tri), sizeof(tri));
    bytes.append(2, '\0');
    write_file(dir / "b.STL", bytes);
    auto stl = read_surface(dir / "b.STL");
    ASSERT_TRUE(stl.ok()) << stl.error().to_string();
    ASSERT_EQ(stl->triangles.size(), 1u);
    EXPECT_DOUBLE_EQ(stl->points[stl->triangles[0][1]].x, 2.0);
}

// ------------------------------------------------------------------------------------------
// write_vtu

TetMesh two_tets() {
    std::vector<Vec3> points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}};
    std::vector<Tet> tets = {{0, 1, 2, 3}, {1, 2, 3, 4}};
    auto mesh = TetMesh::create(points, tets, {7, 9});
    if (!mesh.ok()) throw std::runtime_error(mesh.error().to_string());
    TetMesh m = std::move(mesh).value();
    auto st = m.add_point_field(make_float_field("temp", 1, {1.f, 2.f, 3.f, 4.f, 5.f}));
    if (!st.ok()) throw std::runtime_error(st.error().to_string());
    st = m.add_point_field(make_double_field("vel", 3, std::vector<double>(15, 0.25)));
    if (!st.ok()) throw std::runtime_error(st.error().to_string());
    st = m.add_cell_field(make_double_field("p", 1, {10.0, 20.0}));
    if (!st.ok()) throw std::runtime_error(st.error().to_string());
    return m;
}

TEST(WriteVtu, RoundTrip) {
    TempDir dir;
    const TetMesh mesh = two_tets();
    for (bool binary : {true, false}) {
        SCOPED_TRACE(binary ? "binary" : "ascii");
        WriteVtuOptions options;
        options.binary = binary;
        const fs::path path = dir / (binary ? "b.vtu" : "a.vtu");
        auto st = write_vtu(mesh, path, options);
        ASSERT_TRUE(st.ok()) << st.error().to_string();
        auto back = read_mesh(path);
        ASSERT_TRUE(back.ok()) << back.error().to_string();
        ASSERT_EQ(back->num_points(), mesh.num_points());
        for (std::size_t i = 0; i < mesh.num_points(); ++i) {
            EXPECT_EQ(back->points[i], mesh.points()[i]);
        }
        ASSERT_EQ(back->num_cells(), mesh.num_tets());
        for (std::size_t t = 0; t < mesh.num_tets(); ++t) {
            EXPECT_EQ(back->types[t], CellType::kTetra);
            for (int k = 0; k < 4; ++k) {
                EXPECT_EQ(back->connectivity[4 * t + static_cast<std::size_t>(k)],
                          static_cast<std::int64_t>(
                              mesh.tet(static_cast<CellId>(t))[static_cast<std::size_t>(k)]));
            }
        }
        const Field& temp = field(back->point_fields, "temp");
        EXPECT_FALSE(temp.is_double());
        EXPECT_DOUBLE_EQ(temp.get(4), 5.0);
        EXPECT_EQ(field(back->point_fields, "vel").num_components, 3);
        EXPECT_DOUBLE_EQ(field(back->cell_fields, "p").get(1), 20.0);
        const Field& source = field(back->cell_fields, "source_cell");
        EXPECT_DOUBLE_EQ(source.get(0), 7.0);
        EXPECT_DOUBLE_EQ(source.get(1), 9.0);
        EXPECT_EQ(find_field(back->cell_fields, "virtual"), nullptr);
    }
    // No temporary files left behind.
    int files = 0;
    for (const auto& entry : fs::directory_iterator(dir.path())) {
        (void)entry;
        ++files;
    }
    EXPECT_EQ(files, 2);
}

TEST(WriteVtu, IncludeVirtualAddsArray) {
    TempDir dir;
    TetMesh mesh = two_tets();
    auto st = mesh.append_virtual({{2, 2, 2}}, {{1, 2, 4, 5}});
    ASSERT_TRUE(st.ok()) << st.error().to_string();
    ASSERT_EQ(mesh.num_virtual_tets(), 1u);

    ASSERT_TRUE(write_vtu(mesh, dir / "real.vtu").ok());
    auto real = read_mesh(dir / "real.vtu");
    ASSERT_TRUE(real.ok()) << real.error().to_string();
    EXPECT_EQ(real->num_cells(), 2u);
    EXPECT_EQ(real->num_points(), 5u);
    EXPECT_EQ(find_field(real->cell_fields, "virtual"), nullptr);

    WriteVtuOptions options;
    options.include_virtual = true;
    ASSERT_TRUE(write_vtu(mesh, dir / "all.vtu", options).ok());
    auto all = read_mesh(dir / "all.vtu");
    ASSERT_TRUE(all.ok()) << all.error().to_string();
    ASSERT_EQ(all->num_cells(), 3u);
    EXPECT_EQ(all->num_points(), 6u);
    const Field* virt = find_field(all->cell_fields, "virtual");
    ASSERT_NE(virt, nullptr);
    EXPECT_DOUBLE_EQ(virt->get(0), 0.0);
    EXPECT_DOUBLE_EQ(virt->get(2), 1.0);
    EXPECT_DOUBLE_EQ(field(all->cell_fields, "source_cell").get(2), -1.0);
    EXPECT_DOUBLE_EQ(field(all->cell_fields, "p").get(2), 0.0);
}

TEST(WriteVtu, MissingFolderFailsAndLeavesNoFile) {
    TempDir dir;
    const fs::path path = dir / "no" / "such" / "dir" / "out.vtu";
    auto st = write_vtu(two_tets(), path);
    ASSERT_FALSE(st.ok());
    EXPECT_TRUE(test::one_line(st.error().message));
    EXPECT_NE(st.error().to_string().find("out.vtu"), std::string::npos);
    EXPECT_FALSE(fs::exists(path));
    EXPECT_FALSE(fs::exists(dir / "no"));
}

TEST(WriteVtu, OverwritesAtomically) {
    TempDir dir;
    const fs::path path = dir / "m.vtu";
    write_file(path, "old contents");
    ASSERT_TRUE(write_vtu(two_tets(), path).ok());
    auto back = read_mesh(path);
    ASSERT_TRUE(back.ok()) << back.error().to_string();
    EXPECT_EQ(back->num_cells(), 2u);
}

}  // namespace
}  // namespace tr
