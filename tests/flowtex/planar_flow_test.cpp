// A planar 2D mesh as the flow (mesh/planar_slab.h): the slab's mid-plane carries the 2D
// mesh's field linear on its triangles, exactly; the slab keeps the area (times its thickness)
// and winds no wedge inverted; vectors become tangent; bad 2D meshes are refused; texture
// advection over a quad and over a triangle mesh in uniform flow shifts the picture by v k dt;
// spot noise covers the sheet and moves its spots by v dt.
#include <flowtex/advected_sheets.h>
#include <flowtex/sheet_raster.h>
#include <flowtex/spot_noise_frames.h>
#include <flowvol/point_locator.h>
#include <flowvol/velocity_field.h>
#include <mesh/face_adjacency.h>
#include <mesh/planar_slab.h>
#include <mesh/tetrahedralize.h>
#include <tests/flowtex/fixtures.h>
#include <tests/support/image_shift.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

namespace tr {
namespace {

// An n x n grid over [lo, lo + n h]^2 of the plane origin + s e1 + t e2: quads, or each quad as
// two triangles, or (mixed) quads, triangle pairs and pixel cells by turns; `value(s, t)` as
// the point field "f" and the 2-component point field "velocity" (vx, vy).
struct Grid2D {
    Vec3 origin{0.0}, e1{1, 0, 0}, e2{0, 1, 0};
    double lo = -1.5, h = 0.1;
    int n = 30;
};

enum class Cells { kQuads, kTriangles, kMixed };

UnstructuredMesh grid_2d(const Grid2D& g, Cells cells, double (*value)(double, double),
                         const glm::dvec2& velocity) {
    UnstructuredMesh mesh;
    std::vector<double> f, v;
    for (int j = 0; j <= g.n; ++j) {
        for (int i = 0; i <= g.n; ++i) {
            const double s = g.lo + i * g.h, t = g.lo + j * g.h;
            mesh.points.push_back(g.origin + s * g.e1 + t * g.e2);
            f.push_back(value(s, t));
            v.push_back(velocity.x);
            v.push_back(velocity.y);
        }
    }
    const auto id = [&](int i, int j) { return static_cast<std::int64_t>(j * (g.n + 1) + i); };
    for (int j = 0; j < g.n; ++j) {
        for (int i = 0; i < g.n; ++i) {
            const int kind =
                cells == Cells::kMixed ? (i + j) % 3 : (cells == Cells::kQuads ? 0 : 1);
            if (kind == 0) {
                mesh.add_cell(CellType::kQuad,
                              {id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
            } else if (kind == 1) {
                mesh.add_cell(CellType::kTriangle, {id(i, j), id(i + 1, j), id(i + 1, j + 1)});
                mesh.add_cell(CellType::kTriangle, {id(i, j), id(i + 1, j + 1), id(i, j + 1)});
            } else {  // a pixel (VTK 8): nodes 2 and 3 swapped against a quad; wound clockwise
                mesh.add_cell(static_cast<CellType>(8),
                              {id(i, j), id(i, j + 1), id(i + 1, j), id(i + 1, j + 1)});
            }
        }
    }
    mesh.point_fields.push_back(make_double_field("f", 1, std::move(f)));
    mesh.point_fields.push_back(make_double_field("velocity", 2, std::move(v)));
    return mesh;
}

double wavy(double s, double t) { return std::sin(3.0 * s) + t * t - 0.5 * s * t; }
double zero(double, double) { return 0.0; }

struct Slab {
    PlanarSheet sheet;
    TetMesh tets;
    TetrahedralizeReport report;
};

Slab make_slab(const UnstructuredMesh& mesh) {
    Slab out;
    out.sheet = planar_sheet(mesh).value();
    const UnstructuredMesh slab = planar_slab(mesh, out.sheet).value();
    out.tets = tetrahedralize(slab, {}, &out.report).value();
    return out;
}

TEST(PlanarSlab, TheMidPlaneCarriesTheTrianglesLinearFieldExactly) {
    // A tilted plane, mixed cells, a field far from linear: at random mid-plane points the
    // tets' interpolation equals the linear interpolation on the fan triangle holding the
    // point (quad (a, b, c, d) split along a-c; a pixel likewise in quad order).
    Grid2D g;
    g.origin = Vec3(0.3, -0.2, 1.0);
    g.e1 = glm::normalize(Vec3(1, 0.2, 0.4));
    g.e2 = glm::normalize(glm::cross(Vec3(0.1, 0.3, 1.0), g.e1));
    g.n = 12;
    g.h = 0.25;
    const UnstructuredMesh mesh = grid_2d(g, Cells::kMixed, wavy, {0.0, 0.0});
    const Slab slab = make_slab(mesh);
    const FaceAdjacency adjacency = build_face_adjacency(slab.tets).value();
    const PointLocator locator(slab.tets, adjacency);
    const Field& f = *find_field(slab.tets.point_fields(), "f");
    const Vec3 normal = glm::cross(g.e1, g.e2);
    std::mt19937 random(7);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    double worst = 0;
    int located = 0;
    for (int k = 0; k < 4000; ++k) {
        const int i = static_cast<int>(u(random) * g.n), j = static_cast<int>(u(random) * g.n);
        double a = u(random), b = u(random);
        // The cell's triangles in quad order a-b-c-d = (i,j) (i+1,j) (i+1,j+1) (i,j+1), split
        // along (i,j)-(i+1,j+1) for every kind of cell.
        const bool lower = a >= b;  // triangle (i,j) (i+1,j) (i+1,j+1) when a >= b
        const double s = g.lo + (i + a) * g.h, t = g.lo + (j + b) * g.h;
        const double f00 = wavy(g.lo + i * g.h, g.lo + j * g.h);
        const double f11 = wavy(g.lo + (i + 1) * g.h, g.lo + (j + 1) * g.h);
        const double fx = lower ? wavy(g.lo + (i + 1) * g.h, g.lo + j * g.h)
                                : wavy(g.lo + i * g.h, g.lo + (j + 1) * g.h);
        const double linear =
            lower ? f00 + a * (fx - f00) + b * (f11 - fx) : f00 + b * (fx - f00) + a * (f11 - fx);
        const Vec3 p = g.origin + s * g.e1 + t * g.e2;
        const auto at = locator.locate(p + 1e-12 * normal);
        ASSERT_TRUE(at.has_value()) << s << " " << t;
        ++located;
        double tets_value = 0;
        for (int c = 0; c < 4; ++c) {
            tets_value += at->barycentric[c] * f.get(slab.tets.tet(at->tet)[c]);
        }
        worst = std::max(worst, std::abs(tets_value - linear));
    }
    std::printf("largest difference %.3g over %d points\n", worst, located);
    EXPECT_LT(worst, 1e-9);  // measured 2.2e-15
}

TEST(PlanarSlab, KeepsTheAreaTimesTheThicknessAndWindsNoWedgeInverted) {
    Grid2D g;
    g.n = 20;
    g.h = 0.15;
    for (const Cells cells : {Cells::kQuads, Cells::kTriangles, Cells::kMixed}) {
        const UnstructuredMesh mesh = grid_2d(g, cells, zero, {0.0, 0.0});
        const Slab slab = make_slab(mesh);
        EXPECT_EQ(slab.report.num_inverted_cells, 0u);
        EXPECT_EQ(slab.report.num_degenerate_cells, 0u);
        EXPECT_EQ(slab.sheet.normal, Vec3(0, 0, 1));
        // Every fan triangle of this grid is half a square: sqrt(2 area) = h.
        EXPECT_NEAR(slab.sheet.thickness, g.h, 1e-12);
        const double area = (g.n * g.h) * (g.n * g.h);
        EXPECT_NEAR(slab.tets.real_volume(), area * slab.sheet.thickness, 1e-9 * area);
        EXPECT_NEAR(slab.sheet.point.z, 0.0, 1e-12);
    }
}

TEST(PlanarSlab, VectorsBecomeTangentToThePlane) {
    Grid2D g;
    g.n = 4;
    g.e1 = glm::normalize(Vec3(1, 0, 1));
    g.e2 = Vec3(0, 1, 0);
    UnstructuredMesh mesh = grid_2d(g, Cells::kQuads, zero, {0.5, -0.25});
    std::vector<double> v3;
    for (std::size_t i = 0; i < mesh.points.size(); ++i) v3.insert(v3.end(), {1.0, 2.0, 3.0});
    mesh.point_fields.push_back(make_double_field("v3", 3, v3));
    const PlanarSheet sheet = planar_sheet(mesh).value();
    const UnstructuredMesh slab = planar_slab(mesh, sheet).value();
    ASSERT_EQ(slab.points.size(), 2 * mesh.points.size());
    const Field& v2 = *find_field(slab.point_fields, "velocity");
    const Field& w = *find_field(slab.point_fields, "v3");
    ASSERT_EQ(v2.num_components, 3);
    const Vec3 expected2 =
        Vec3(0.5, -0.25, 0.0) - glm::dot(Vec3(0.5, -0.25, 0.0), sheet.normal) * sheet.normal;
    const Vec3 expected3 = Vec3(1, 2, 3) - glm::dot(Vec3(1, 2, 3), sheet.normal) * sheet.normal;
    for (std::size_t i = 0; i < slab.points.size(); ++i) {
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(v2.get(i, c), expected2[c], 1e-12);
            EXPECT_NEAR(w.get(i, c), expected3[c], 1e-12);
        }
    }
}

TEST(PlanarSlab, RefusesWhatIsNotAPlanarMesh) {
    Grid2D g;
    g.n = 4;
    UnstructuredMesh curved = grid_2d(g, Cells::kQuads, zero, {0.0, 0.0});
    curved.points[7].z = 0.01;
    const auto not_planar = planar_sheet(curved);
    ASSERT_FALSE(not_planar.ok());
    EXPECT_NE(not_planar.error().message.find("not planar: point "), std::string::npos)
        << not_planar.error().message;

    UnstructuredMesh flat = grid_2d(g, Cells::kQuads, zero, {0.0, 0.0});
    for (Vec3& p : flat.points) p = Vec3(p.x, 0.0, 0.0);  // every cell on a line
    const auto no_area = planar_sheet(flat);
    ASSERT_FALSE(no_area.ok());
    EXPECT_NE(no_area.error().message.find("have no area"), std::string::npos);

    UnstructuredMesh out_of_range = grid_2d(g, Cells::kQuads, zero, {0.0, 0.0});
    out_of_range.connectivity[5] = 1000;
    const auto bad_index = planar_sheet(out_of_range);
    ASSERT_FALSE(bad_index.ok());
    EXPECT_NE(bad_index.error().message.find("names point 1000"), std::string::npos);

    // Boundary lines beside the quads are passed over (no wedge), a tet is not.
    UnstructuredMesh with_lines = grid_2d(g, Cells::kQuads, zero, {0.0, 0.0});
    with_lines.add_cell(static_cast<CellType>(3), {0, 1});
    with_lines.add_cell(static_cast<CellType>(4), {0, 1, 2});
    with_lines.cell_fields.push_back(
        make_double_field("id", 1, std::vector<double>(with_lines.num_cells(), 1.0)));
    ASSERT_TRUE(is_surface_mesh(with_lines));
    const auto lines_slab = planar_slab(with_lines, planar_sheet(with_lines).value());
    ASSERT_TRUE(lines_slab.ok());
    EXPECT_EQ(lines_slab->num_cells(), 2u * 16u);  // two wedges a quad, none for the lines

    UnstructuredMesh mixed = grid_2d(g, Cells::kQuads, zero, {0.0, 0.0});
    mixed.points.push_back(Vec3(0, 0, 1));
    mixed.add_cell(CellType::kTetra, {0, 1, 5, static_cast<std::int64_t>(mixed.points.size() - 1)});
    EXPECT_FALSE(is_surface_mesh(mixed));
    EXPECT_FALSE(planar_sheet(mixed).ok());

    UnstructuredMesh short_field = grid_2d(g, Cells::kQuads, zero, {0.0, 0.0});
    short_field.cell_fields.push_back(make_double_field("c", 1, {1.0, 2.0}));
    const auto bad_field = planar_slab(short_field, planar_sheet(short_field).value());
    ASSERT_FALSE(bad_field.ok());
    EXPECT_NE(bad_field.error().message.find("cell array 'c' has 2 tuples"), std::string::npos);
}

// Texture advection over the slab of a 2D mesh in uniform flow v: frame k is frame 0 moved by
// v k dt (the closed form of TextureAdvection.UniformFlowShiftsThePictureByVKdt, here with the
// flow taken from the 2D mesh itself through the slab's tets).
double worst_shift_error(Cells cells) {
    Grid2D g;  // [-1.5, 1.5]^2, 30 squares a side
    const glm::dvec2 v(0.3, 0.2);
    const UnstructuredMesh mesh = grid_2d(g, cells, zero, v);
    const Slab slab = make_slab(mesh);
    const FaceAdjacency adjacency = build_face_adjacency(slab.tets).value();
    const VelocityField velocity =
        VelocityField::steady(slab.tets, *find_field(slab.tets.point_fields(), "velocity")).value();
    AdvectedSheetsOptions options;
    options.slices.push_back({slab.sheet.point, slab.sheet.normal});
    options.sheet_resolution = 192;
    options.dt = 0.05;
    options.reinject_frames = 0;
    options.texture_size = 64;
    options.texture_feature = 2;
    options.texture_period = 1.0;  // 64 texels over 64 pixels
    const auto sheets = AdvectedSheets::create(slab.tets, adjacency, velocity, options).value();
    const CameraFrame frame = testing::top_view(128);
    const std::vector<float> frame0 =
        rasterize_sheet_values(frame, sheets->views(0), sheets->texture());
    double worst = 0;
    for (int k = 1; k <= 20; ++k) {
        sheets->advance();
        if (k % 5 != 0) continue;
        const std::vector<float> frame_k =
            rasterize_sheet_values(frame, sheets->views(0), sheets->texture());
        const glm::dvec2 expected(v.x * k * 0.05 * 64, -v.y * k * 0.05 * 64);
        const auto est = testing::estimate_shift(frame0, frame_k, 128, 128, expected, 3, 4);
        worst = std::max(worst, glm::length(est.shift - expected));
        std::printf("frame %d: expected (%.3f, %.3f) px, found (%.3f, %.3f), peak %.4f\n", k,
                    expected.x, expected.y, est.shift.x, est.shift.y, est.peak);
        EXPECT_GT(est.peak, 0.98);
    }
    return worst;
}

TEST(PlanarFlowAdvection, UniformFlowOnQuadsShiftsThePictureByVKdt) {
    const double worst = worst_shift_error(Cells::kQuads);
    // The bound is half a pixel; measured 0.028 px (the estimator's parabola bias, as
    // on an analytic flow).
    EXPECT_LT(worst, 0.5);
    EXPECT_LT(worst, 0.05);
}

TEST(PlanarFlowAdvection, UniformFlowOnTrianglesShiftsThePictureByVKdt) {
    const double worst = worst_shift_error(Cells::kTriangles);
    EXPECT_LT(worst, 0.5);
    EXPECT_LT(worst, 0.05);  // measured 0.028 px
}

TEST(PlanarFlowSpotNoise, SpotsCoverTheSheetAndMoveByVdt) {
    Grid2D g;
    g.n = 20;
    const glm::dvec2 v(0.3, -0.1);
    const UnstructuredMesh mesh = grid_2d(g, Cells::kMixed, zero, v);
    const Slab slab = make_slab(mesh);
    const FaceAdjacency adjacency = build_face_adjacency(slab.tets).value();
    const VelocityField velocity =
        VelocityField::steady(slab.tets, *find_field(slab.tets.point_fields(), "velocity")).value();
    SpotNoiseFramesOptions options;
    options.planar = slab.sheet;
    options.spots.count = 2000;
    options.spots.dt = 0.02;
    const auto run = start_spot_noise(slab.tets, adjacency, velocity, options).value();
    SpotNoise& spots = *run->spots;
    EXPECT_EQ(spots.band_tets(), slab.tets.num_real_tets());  // the whole slab is the band
    // Spread over the sheet: each quarter of the square holds a quarter of the spots (binomial
    // sd 19 of 500; bound 5 sd).
    int quarter[4] = {0, 0, 0, 0};
    const double mid = g.lo + 0.5 * g.n * g.h;  // the square's centre, -0.5
    for (const Vec3& p : spots.positions()) {
        ++quarter[(p.x > mid ? 1 : 0) + (p.y > mid ? 2 : 0)];
    }
    for (const int q : quarter) EXPECT_NEAR(q, 500, 100);
    const std::vector<Vec3> before(spots.positions().begin(), spots.positions().end());
    const std::vector<std::uint32_t> generations(spots.generations().begin(),
                                                 spots.generations().end());
    spots.advance();
    double worst = 0, height = 0;
    std::size_t moved = 0;
    for (std::size_t i = 0; i < spots.size(); ++i) {
        height = std::max(height, std::abs(spots.positions()[i].z));
        if (spots.generations()[i] != generations[i]) continue;
        ++moved;
        const Vec3 expected = before[i] + 0.02 * Vec3(v.x, v.y, 0.0);
        worst = std::max(worst, glm::length(spots.positions()[i] - expected));
    }
    std::printf("%zu spots moved, largest error %.3g, largest height %.3g\n", moved, worst, height);
    EXPECT_GT(moved, 1900u);  // the rest left through the outflow side or aged out
    EXPECT_LT(worst, 1e-9);   // uniform flow: RK4 exact
    EXPECT_LT(height, 0.5 * slab.sheet.thickness);
}

}  // namespace
}  // namespace tr
