// Reads every data set of /work/shared/data (README's "Which file to open" table, the PLOT3D
// originals, the MFEM .mesh originals and the legacy structured points) and checks counts and
// arrays against each SOURCE.md.
// Skipped when the folder is absent, except in CI (CI=true), where that is a failure.

#include <io/read_mesh.h>
#include <tests/io/io_test_util.h>

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <map>

namespace tr {
namespace {

namespace fs = std::filesystem;

struct ArraySpec {
    std::string name;
    int num_components;
    bool float32;               // stored as float32 (else float64)
    double lo = NAN, hi = NAN;  // range of component 0 (NaN: not checked)
};

struct DataSpec {
    std::string file;
    std::size_t num_points;
    std::size_t num_cells;
    std::map<CellType, std::size_t> cells_by_type;
    std::vector<ArraySpec> point_arrays;
    std::vector<ArraySpec> cell_arrays;
    std::string format_prefix;
};

void PrintTo(const DataSpec& spec, std::ostream* os) { *os << spec.file; }

void check_arrays(const std::vector<Field>& fields, const std::vector<ArraySpec>& specs,
                  std::size_t num_tuples, const char* kind) {
    for (const ArraySpec& a : specs) {
        SCOPED_TRACE(std::string(kind) + " array " + a.name);
        const Field* f = find_field(fields, a.name);
        ASSERT_NE(f, nullptr) << "missing";
        EXPECT_EQ(f->num_components, a.num_components);
        EXPECT_EQ(!f->is_double(), a.float32);
        EXPECT_EQ(f->num_tuples(), num_tuples);
        if (!std::isnan(a.lo)) {
            const auto [lo, hi] = field_range(*f, 0);
            const double tol = 1e-4 * std::max({1.0, std::abs(a.lo), std::abs(a.hi)});
            EXPECT_NEAR(lo, a.lo, tol);
            EXPECT_NEAR(hi, a.hi, tol);
        }
    }
}

class RealData : public ::testing::TestWithParam<DataSpec> {};

TEST_P(RealData, CountsAndArraysMatchSource) {
    TR_REQUIRE_SHARED_DATA();
    const DataSpec& spec = GetParam();
    const fs::path path = test::shared_data_dir() / spec.file;
    auto mesh = read_mesh(path);
    ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
    EXPECT_EQ(mesh->num_points(), spec.num_points);
    EXPECT_EQ(mesh->num_cells(), spec.num_cells);
    std::map<CellType, std::size_t> by_type;
    for (CellType t : mesh->types) ++by_type[t];
    EXPECT_EQ(by_type, spec.cells_by_type);
    check_arrays(mesh->point_fields, spec.point_arrays, mesh->num_points(), "point");
    check_arrays(mesh->cell_fields, spec.cell_arrays, mesh->num_cells(), "cell");
    EXPECT_EQ(mesh->format.rfind(spec.format_prefix, 0), 0u) << mesh->format;
}

using CT = CellType;

std::string spec_name(const ::testing::TestParamInfo<DataSpec>& info) {
    std::string name = info.param.file;
    for (char& ch : name) {
        if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
    }
    return name;
}

const std::vector<ArraySpec> kPlot3dArrays = {{"Density", 1, true},
                                              {"Momentum", 3, true},
                                              {"StagnationEnergy", 1, true},
                                              {"Velocity", 3, true}};

INSTANTIATE_TEST_SUITE_P(
    SharedData, RealData,
    ::testing::Values(DataSpec{"disk_out_ref/disk_out_ref.ex2",
                               8499,
                               7472,
                               {{CT::kHexahedron, 7472}},
                               {{"Temp", 1, false, 293.15, 913.15},
                                {"V", 3, false, -19.9491, 19.9491},
                                {"Pres", 1, false, 0.00678552, 0.0288185},
                                {"AsH3", 1, false},
                                {"GaMe3", 1, false},
                                {"CH4", 1, false},
                                {"H2", 1, false, 0.807613, 0.917688}},
                               {{"ObjectId", 1, false, 1, 1}},
                               "Exodus II"},
                      DataSpec{"bluntfin/bluntfin.vtu",
                               40960,
                               37479,
                               {{CT::kHexahedron, 37479}},
                               {{"Density", 1, true, 0.1926, 4.9775},
                                {"Momentum", 3, true, -2.1835, 5.7903},
                                {"Pressure", 1, true},
                                {"StagnationEnergy", 1, true},
                                {"Velocity", 3, true}},
                               {},
                               "VTK XML unstructured grid"},
                      DataSpec{"bluntfin/bluntfinxyz.bin",
                               40960,
                               37479,
                               {{CT::kHexahedron, 37479}},
                               {{"Density", 1, true, 0.1926, 4.9775},
                                {"Momentum", 3, true, -2.1835, 5.7903},
                                {"StagnationEnergy", 1, true, 0.768957, 25.161},
                                {"Velocity", 3, true}},
                               {},
                               "PLOT3D"},
                      DataSpec{"lox_post/lox_post.vtu",
                               109744,
                               102675,
                               {{CT::kHexahedron, 102675}},
                               {{"Density", 1, true, 1, 1},
                                {"IBlank", 1, false, -1, 1},
                                {"Momentum", 3, true},
                                {"StagnationEnergy", 1, true},
                                {"Velocity", 3, true}},
                               {},
                               "VTK XML unstructured grid"},
                      DataSpec{"lox_post/postxyz.bin",
                               109744,
                               102675,
                               {{CT::kHexahedron, 102675}},
                               {{"Density", 1, true, 1, 1},
                                {"Momentum", 3, true, -0.215009, 1.36175},
                                {"StagnationEnergy", 1, true, -0.541506, 4.39584},
                                {"Velocity", 3, true}},
                               {},
                               "PLOT3D"},
                      DataSpec{"combustor/combustor.vtu",
                               47025,
                               43008,
                               {{CT::kHexahedron, 43008}},
                               {{"Density", 1, true, 0.197813, 0.710419},
                                {"Momentum", 3, true},
                                {"StagnationEnergy", 1, true},
                                {"Velocity", 3, true}},
                               {},
                               "VTK XML unstructured grid"},
                      DataSpec{"combustor/combxyz.bin",
                               47025,
                               43008,
                               {{CT::kHexahedron, 43008}},
                               {{"Density", 1, true, 0.197813, 0.710419},
                                {"Momentum", 3, true, -368.541, 368.378},
                                {"StagnationEnergy", 1, true, 0, 0},
                                {"Velocity", 3, true}},
                               {},
                               "PLOT3D"},
                      DataSpec{"office/office.binary.vtk",
                               8400,
                               7220,
                               {{CT::kHexahedron, 7220}},
                               {{"scalars", 1, true, -3.86956, 0.71856},
                                {"vectors", 3, true, -0.672869, 0.204172}},
                               {},
                               "VTK legacy structured grid"},
                      DataSpec{"can/can.vtu",
                               6724,
                               4800,
                               {{CT::kHexahedron, 4800}},
                               {{"DISPL", 3, false, -7.16961, 0.887777},
                                {"VEL", 3, false},
                                {"ACCL", 3, false},
                                {"GlobalNodeId", 1, false, 1, 6724},
                                {"PedigreeNodeId", 1, false, 1, 6724}},
                               {{"EQPS", 1, false, 0.0215831, 2.89394}},
                               "VTK XML unstructured grid"},
                      DataSpec{"angular_sector/AngularSector.vtk",
                               10141,
                               7776,
                               {{CT::kHexahedron, 7632}, {CT::kPyramid, 144}},
                               {{"PointId", 1, false, 0, 9126}},
                               {{"CellId", 1, false, 0, 7775}},
                               "VTK legacy unstructured grid"},
                      DataSpec{"fea_bracket/dataset.vtu",
                               102578,
                               56786,
                               {{CT::kQuadraticTetra, 56786}},
                               {},
                               {{"Equivalent (von-Mises) Stress (psi)", 1, true, 0.014035, 23.269}},
                               "VTK XML unstructured grid"},
                      DataSpec{"tetra_mesh/tetraMesh.vtk",
                               55,
                               160,
                               {{CT::kTetra, 160}},
                               {{"scalars", 1, false, 0, 4}},
                               {},
                               "VTK legacy unstructured grid"},
                      DataSpec{"cylinder_tets/CylinderLinear.vtk",
                               465,
                               1522,
                               {{CT::kTetra, 1522}},
                               {{"velocity", 3, false, -0.0567848, 0.158882},
                                {"vel_norm", 1, false, 0, 1.0044}},
                               {},
                               "VTK legacy unstructured grid"},
                      DataSpec{"cylinder_tets_quadratic/CylinderQuadratic.vtk",
                               2814,
                               1522,
                               {{CT::kQuadraticTetra, 1522}},
                               {{"velocity", 3, false, -0.294561, 0.285526},
                                {"pressure", 1, false, -98.4392, 7234.49},
                                {"velocity_norm", 1, false}},
                               {{"velocity", 3, false},
                                {"pressure", 1, false, -13.8635, 5059.73},
                                {"velocity_norm", 1, false},
                                {"Re", 1, false, 0, 0}},
                               "VTK legacy unstructured grid"},
                      DataSpec{"wedge_blocks/mesh_fs8.exo",
                               1400,
                               1344,
                               {{CT::kWedge, 1344}},
                               {},
                               {{"ObjectId", 1, false, 1, 3}},
                               "Exodus II"},
                      DataSpec{"prisms_penta_hexa/PentaHexa.vtk",
                               401,
                               210,
                               {{CT::kPentagonalPrism, 60}, {CT::kHexagonalPrism, 150}},
                               {{"scalar2", 1, true, 0, 1}},
                               {{"scalar1", 1, false, 1, 210}},
                               "VTK legacy unstructured grid"},
                      DataSpec{"letter_a_tets/a_grid.vtk",
                               1317,
                               4802,
                               {{CT::kTetra, 4802}},
                               {},
                               {},
                               "VTK legacy unstructured grid"},
                      DataSpec{"mfem_escher/escher.vtu",
                               26,
                               42,
                               {{CT::kTetra, 42}},
                               {},
                               {{"attribute", 1, false, 1, 1}},
                               "VTK XML unstructured grid"},
                      DataSpec{"mfem_escher/escher.mesh",
                               26,
                               42,
                               {{CT::kTetra, 42}},
                               {},
                               {{"attribute", 1, false, 1, 1}},
                               "MFEM mesh v1.0"},
                      DataSpec{"mfem_fichera_mixed/fichera-mixed.vtu",
                               26,
                               14,
                               {{CT::kTetra, 5}, {CT::kHexahedron, 3}, {CT::kWedge, 6}},
                               {},
                               {{"attribute", 1, false, 1, 1}},
                               "VTK XML unstructured grid"},
                      DataSpec{"mfem_fichera_mixed/fichera-mixed.mesh",
                               26,
                               14,
                               {{CT::kTetra, 5}, {CT::kHexahedron, 3}, {CT::kWedge, 6}},
                               {},
                               {{"attribute", 1, false, 1, 1}},
                               "MFEM mesh v1.0"}),
    spec_name);

// Regular lattices in legacy binary .vtk (iron_protein: a VTK 1.0 header with blank lines).
INSTANTIATE_TEST_SUITE_P(StructuredPoints, RealData,
                         ::testing::Values(DataSpec{"iron_protein/ironProt.vtk",
                                                    314432,
                                                    300763,
                                                    {{CT::kHexahedron, 300763}},
                                                    {{"scalars", 1, false, 0, 255}},
                                                    {},
                                                    "VTK legacy structured points"},
                                           DataSpec{"carotid/carotid.vtk",
                                                    167580,
                                                    158400,
                                                    {{CT::kHexahedron, 158400}},
                                                    {{"scalars", 1, true, 0, 580},
                                                     {"vectors", 3, true, -11.5634, 16.6176}},
                                                    {},
                                                    "VTK legacy structured points"}),
                         spec_name);

// PLOT3D read directly gives the same grid as the converted .vtu next to it (same point order).
TEST(RealDataPlot3d, SameGridAsConvertedVtu) {
    TR_REQUIRE_SHARED_DATA();
    const fs::path data = test::shared_data_dir();
    for (const auto& [xyz, vtu] : std::vector<std::pair<std::string, std::string>>{
             {"bluntfin/bluntfinxyz.bin", "bluntfin/bluntfin.vtu"},
             {"lox_post/postxyz.bin", "lox_post/lox_post.vtu"},
             {"combustor/combxyz.bin", "combustor/combustor.vtu"}}) {
        SCOPED_TRACE(xyz);
        auto a = read_mesh(data / xyz);
        auto b = read_mesh(data / vtu);
        ASSERT_TRUE(a.ok()) << a.error().to_string();
        ASSERT_TRUE(b.ok()) << b.error().to_string();
        ASSERT_EQ(a->num_points(), b->num_points());
        for (std::size_t i = 0; i < a->num_points(); i += 97)
            ASSERT_EQ(a->points[i], b->points[i]) << i;
        ASSERT_EQ(a->connectivity.size(), b->connectivity.size());
        // Same hexahedra, same node order (point id = i + ni * (j + nj * k) in both).
        for (std::size_t c = 0; c < a->num_cells(); c += 101) {
            std::vector<std::int64_t> x(a->connectivity.begin() + a->offsets[c],
                                        a->connectivity.begin() + a->offsets[c + 1]);
            std::vector<std::int64_t> y(b->connectivity.begin() + b->offsets[c],
                                        b->connectivity.begin() + b->offsets[c + 1]);
            EXPECT_EQ(x, y) << "cell " << c;
        }
        EXPECT_NEAR(test::total_abs_volume(*a), test::total_abs_volume(*b),
                    1e-9 * test::total_abs_volume(*b));
        const Field* da = find_field(a->point_fields, "Density");
        const Field* db = find_field(b->point_fields, "Density");
        ASSERT_NE(da, nullptr);
        ASSERT_NE(db, nullptr);
        for (std::size_t i = 0; i < a->num_points(); i += 89)
            ASSERT_EQ(da->get(i), db->get(i)) << i;
    }
}

// The MFEM originals give the same cells as the converted .vtu files, and positive volumes.
TEST(RealDataMfem, SameCellsAsConvertedVtu) {
    TR_REQUIRE_SHARED_DATA();
    const fs::path data = test::shared_data_dir();
    for (const auto& [mesh_file, vtu, volume] :
         std::vector<std::tuple<std::string, std::string, double>>{
             {"mfem_escher/escher.mesh", "mfem_escher/escher.vtu", 6.43142},
             {"mfem_fichera_mixed/fichera-mixed.mesh", "mfem_fichera_mixed/fichera-mixed.vtu",
              7.0}}) {
        SCOPED_TRACE(mesh_file);
        auto a = read_mesh(data / mesh_file);
        auto b = read_mesh(data / vtu);
        ASSERT_TRUE(a.ok()) << a.error().to_string();
        ASSERT_TRUE(b.ok()) << b.error().to_string();
        ASSERT_EQ(a->num_points(), b->num_points());
        for (std::size_t i = 0; i < a->num_points(); ++i)
            EXPECT_EQ(a->points[i], b->points[i]) << i;
        EXPECT_EQ(a->types, b->types);
        EXPECT_EQ(a->offsets, b->offsets);
        EXPECT_EQ(a->connectivity, b->connectivity);
        EXPECT_NEAR(test::total_abs_volume(*a), volume, 1e-5);
        double signed_volume = 0.0;
        for (std::size_t c = 0; c < a->num_cells(); ++c) signed_volume += test::cell_volume(*a, c);
        EXPECT_NEAR(signed_volume, volume, 1e-5) << "all cells positive in VTK's convention";
    }
}

TEST(RealDataExodus, TimeStepsAndSideSets) {
    TR_REQUIRE_SHARED_DATA();
    const fs::path data = test::shared_data_dir();
    auto disk = read_mesh(data / "disk_out_ref" / "disk_out_ref.ex2");
    ASSERT_TRUE(disk.ok()) << disk.error().to_string();
    EXPECT_EQ(disk->time_values.size(), 1u);
    EXPECT_EQ(disk->time_step, 0);
    EXPECT_EQ(disk->surfaces.size(), 7u);
    for (const SurfaceMesh& s : disk->surfaces) {
        EXPECT_FALSE(s.name.empty());
        EXPECT_FALSE(s.triangles.empty()) << s.name;
        for (const auto& tri : s.triangles) {
            for (std::uint32_t id : tri) ASSERT_LT(id, s.points.size()) << s.name;
        }
    }

    auto wedges = read_mesh(data / "wedge_blocks" / "mesh_fs8.exo");
    ASSERT_TRUE(wedges.ok()) << wedges.error().to_string();
    EXPECT_TRUE(wedges->time_values.empty());
    EXPECT_EQ(wedges->surfaces.size(), 8u);
    // Three blocks: ObjectId 1, 2, 3 all present.
    const Field* object = find_field(wedges->cell_fields, "ObjectId");
    ASSERT_NE(object, nullptr);
    std::map<int, int> per_block;
    for (std::size_t c = 0; c < wedges->num_cells(); ++c)
        ++per_block[static_cast<int>(object->get(c))];
    EXPECT_EQ(per_block.size(), 3u);
    // Every wedge is inverted by VTK's convention (SOURCE.md).
    std::size_t negative = 0;
    for (std::size_t c = 0; c < wedges->num_cells(); ++c)
        negative += test::cell_volume(*wedges, c) < 0;
    EXPECT_EQ(negative, 1344u);
    EXPECT_NEAR(test::total_abs_volume(*wedges), 298.657, 1e-2);
}

TEST(RealDataVolume, StructuredOfficeVolume) {
    TR_REQUIRE_SHARED_DATA();
    auto office = read_mesh(test::shared_data_dir() / "office" / "office.binary.vtk");
    ASSERT_TRUE(office.ok()) << office.error().to_string();
    EXPECT_NEAR(test::total_abs_volume(*office), 50.1986, 1e-3);
    // point id = i + 21 * (j + 20 * k): the first hexahedron.
    const std::vector<std::int64_t> first(office->connectivity.begin(),
                                          office->connectivity.begin() + 8);
    EXPECT_EQ(first, (std::vector<std::int64_t>{0, 1, 22, 21, 420, 421, 442, 441}));
}

// A regular lattice read as hexahedra: point i + ni (j + nj k) at origin + spacing * (i, j, k),
// (ni - 1)(nj - 1)(nk - 1) cells of volume sx sy sz, cell 0 on points 0, 1, ni + 1, ni, ...
void expect_lattice(const UnstructuredMesh& m, const std::array<std::int64_t, 3>& dims,
                    const Vec3& origin, const Vec3& spacing) {
    const auto [ni, nj, nk] = dims;
    ASSERT_EQ(m.num_points(), static_cast<std::size_t>(ni * nj * nk));
    std::size_t off_lattice = 0;
    for (std::int64_t k = 0; k < nk; ++k) {
        for (std::int64_t j = 0; j < nj; ++j) {
            for (std::int64_t i = 0; i < ni; ++i) {
                const Vec3 want = origin + spacing * Vec3(i, j, k);
                off_lattice += m.points[static_cast<std::size_t>(i + ni * (j + nj * k))] != want;
            }
        }
    }
    EXPECT_EQ(off_lattice, 0u);
    Vec3 lo = m.points[0], hi = m.points[0];
    for (const Vec3& p : m.points) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    EXPECT_EQ(lo, origin);
    EXPECT_EQ(hi, origin + spacing * Vec3(ni - 1, nj - 1, nk - 1));
    const std::int64_t cells = (ni - 1) * (nj - 1) * (nk - 1);
    ASSERT_EQ(m.num_cells(), static_cast<std::size_t>(cells));
    const std::int64_t nij = ni * nj;
    const std::vector<std::int64_t> first(m.connectivity.begin(), m.connectivity.begin() + 8);
    EXPECT_EQ(first,
              (std::vector<std::int64_t>{0, 1, ni + 1, ni, nij, nij + 1, nij + ni + 1, nij + ni}));
    EXPECT_NEAR(test::total_abs_volume(m),
                static_cast<double>(cells) * spacing.x * spacing.y * spacing.z, 1e-6 * cells);
}

double field_sum(const Field& f, int component) {
    double sum = 0.0;
    for (std::size_t i = 0; i < f.num_tuples(); ++i) sum += f.get(i, component);
    return sum;
}

// iron_protein/SOURCE.md: 68 x 68 x 68, spacing 1 (written as ASPECT_RATIO), origin 0, VTK 1.0
// binary with blank lines in its header; `scalars` unsigned char 0 .. 255, no other array.
TEST(RealDataStructuredPoints, IronProtein) {
    TR_REQUIRE_SHARED_DATA();
    auto m = read_mesh(test::shared_data_dir() / "iron_protein" / "ironProt.vtk");
    ASSERT_TRUE(m.ok()) << m.error().to_string();
    EXPECT_EQ(m->format, "VTK legacy structured points");
    expect_lattice(*m, {68, 68, 68}, Vec3(0, 0, 0), Vec3(1, 1, 1));
    ASSERT_EQ(m->point_fields.size(), 1u);
    EXPECT_TRUE(m->cell_fields.empty());
    const Field& s = m->point_fields[0];
    EXPECT_EQ(s.name, "scalars");
    EXPECT_EQ(s.num_components, 1);
    EXPECT_EQ(field_range(s, 0), std::make_pair(0.0, 255.0));
    // Beyond SOURCE.md, measured with VTK 9.1's vtkDataSetReader (python3-vtk9) on the same
    // file: every byte lands where VTK puts it.
    EXPECT_EQ(field_sum(s, 0), 4131089.0);
    EXPECT_EQ(s.get(34 + 68 * (34 + 68 * 34)), 131.0);  // the lattice centre
    std::size_t zeros = 0;
    for (std::size_t i = 0; i < s.num_tuples(); ++i) zeros += s.get(i) == 0.0;
    EXPECT_EQ(zeros, 207733u);
}

// carotid/SOURCE.md: 76 x 49 x 45, spacing 1, origin (100, 80, 1), VTK 3.0 binary; `scalars`
// float 0 .. 580, `vectors` float with components -11.56 .. 16.62, -22.63 .. 15.61,
// -17.47 .. 9.76 and magnitude 0 .. 22.69; no cell data.
TEST(RealDataStructuredPoints, CarotidWithVectors) {
    TR_REQUIRE_SHARED_DATA();
    auto m = read_mesh(test::shared_data_dir() / "carotid" / "carotid.vtk");
    ASSERT_TRUE(m.ok()) << m.error().to_string();
    EXPECT_EQ(m->format, "VTK legacy structured points");
    expect_lattice(*m, {76, 49, 45}, Vec3(100, 80, 1), Vec3(1, 1, 1));
    ASSERT_EQ(m->point_fields.size(), 2u);
    EXPECT_TRUE(m->cell_fields.empty());
    const Field* s = find_field(m->point_fields, "scalars");
    const Field* v = find_field(m->point_fields, "vectors");
    ASSERT_NE(s, nullptr);
    ASSERT_NE(v, nullptr);
    EXPECT_FALSE(s->is_double());
    EXPECT_FALSE(v->is_double());
    ASSERT_EQ(s->num_components, 1);
    ASSERT_EQ(v->num_components, 3);
    EXPECT_EQ(field_range(*s, 0), std::make_pair(0.0, 580.0));
    // Exact float ranges from VTK 9.1 (SOURCE.md rounds them to 0.01).
    const double want[3][2] = {{-11.563380241394043, 16.617647171020508},
                               {-22.628570556640625, 15.613636016845703},
                               {-17.465517044067383, 9.759259223937988}};
    for (int c = 0; c < 3; ++c) {
        const auto [lo, hi] = field_range(*v, c);
        EXPECT_EQ(lo, want[c][0]) << "component " << c;
        EXPECT_EQ(hi, want[c][1]) << "component " << c;
    }
    double min_mag = 1e300, max_mag = 0.0;
    for (std::size_t i = 0; i < v->num_tuples(); ++i) {
        const double mag = std::sqrt(v->get(i, 0) * v->get(i, 0) + v->get(i, 1) * v->get(i, 1) +
                                     v->get(i, 2) * v->get(i, 2));
        min_mag = std::min(min_mag, mag);
        max_mag = std::max(max_mag, mag);
    }
    EXPECT_EQ(min_mag, 0.0);
    EXPECT_NEAR(max_mag, 22.694927991153424, 1e-9);  // VTK 9.1: 22.694927991153424
    // Measured with VTK 9.1 on the same file: the fastest point, (143, 102, 28), and sums.
    EXPECT_EQ(m->points[102263], Vec3(143, 102, 28));
    EXPECT_EQ(v->get(102263, 1), -22.628570556640625);
    EXPECT_EQ(field_sum(*s, 0), 16598647.0);
    EXPECT_NEAR(field_sum(*v, 0), -1112.633641921065, 1e-6);
}

}  // namespace
}  // namespace tr
