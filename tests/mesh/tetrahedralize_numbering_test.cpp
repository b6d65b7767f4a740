// The conforming split does not depend on numbering: renumbered meshes and meshes cut into
// pieces (each piece with its own numbering) give the same tets, as sets of coordinates; every
// cell type, tangled cells included, stays conforming.
#include <mesh/face_adjacency.h>
#include <mesh/tetrahedralize.h>
#include <tests/support/mixed_grid.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <iterator>
#include <map>
#include <random>
#include <set>
#include <string>
#include <vector>

namespace tr {
namespace {

using testing::box_boundary_triangles;
using testing::extract_cells;
using testing::make_mixed_grid;
using testing::make_prism_stack;
using testing::MixedGridOptions;
using testing::PrismStackOptions;
using testing::random_rotation_scale;
using testing::shuffle_mesh;

// A tet as its four corners' coordinates (sorted lexicographically) and the value of the cell
// field "cell" it carries (the input cell it came from, numbered before any renumbering).
using CoordinateTet = std::array<double, 13>;

std::vector<CoordinateTet> coordinate_tets(const TetMesh& mesh) {
    const Field* cell = find_field(mesh.cell_fields(), "cell");
    std::vector<CoordinateTet> out;
    out.reserve(mesh.num_tets());
    for (CellId t = 0; t < mesh.num_tets(); ++t) {
        std::array<std::array<double, 3>, 4> corners;
        for (int k = 0; k < 4; ++k) {
            const Vec3& p = mesh.point(mesh.tet(t)[k]);
            corners[k] = {p.x, p.y, p.z};
        }
        std::sort(corners.begin(), corners.end());
        CoordinateTet c;
        for (int k = 0; k < 4; ++k)
            for (int i = 0; i < 3; ++i) c[3 * k + i] = corners[k][i];
        c[12] = cell ? cell->get(t) : -1.0;
        out.push_back(c);
    }
    std::sort(out.begin(), out.end());
    return out;
}

// Tets in `a` and not in `b` plus tets in `b` and not in `a` (as multisets).
std::size_t count_differences(const std::vector<CoordinateTet>& a,
                              const std::vector<CoordinateTet>& b) {
    std::vector<CoordinateTet> d;
    std::set_symmetric_difference(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(d));
    return d.size();
}

// A mesh of the corpus and what a conforming split of it must show.
struct Case {
    std::string name;
    UnstructuredMesh mesh;
    std::size_t boundary_triangles;  // unshared tet faces of a conforming split
    bool tangled;                    // some cells are expected to be tangled
};

// Every cell type, with and without ties in x (axis-aligned grids), duplicated points, twisted
// and jittered (tangled) cells. Cell field "cell" numbers the cells.
std::vector<Case> corpus(std::uint32_t seed) {
    std::vector<Case> cases;
    std::mt19937 rng(seed);
    auto grid = [&](const std::string& name, MixedGridOptions o, bool tangled) {
        o.seed = seed;
        o.nx = 2 + static_cast<int>(rng() % 3);
        o.ny = 2 + static_cast<int>(rng() % 3);
        o.nz = 2 + static_cast<int>(rng() % 3);
        cases.push_back({name, make_mixed_grid(o), box_boundary_triangles(o), tangled});
    };
    MixedGridOptions rotated;
    rotated.linear = random_rotation_scale(rng);
    grid("rotated", rotated, false);
    MixedGridOptions axis_aligned;  // many points share x, or x and y: ties go to y, z
    axis_aligned.p_tets = 0.4;
    grid("axis-aligned", axis_aligned, false);
    MixedGridOptions voxels;
    voxels.voxels = true;
    grid("voxels", voxels, false);
    MixedGridOptions quadratic;
    quadratic.quadratic = true;
    quadratic.linear = random_rotation_scale(rng);
    grid("quadratic", quadratic, false);
    MixedGridOptions duplicated;
    duplicated.duplicate_points = true;
    grid("duplicated points", duplicated, false);
    MixedGridOptions jittered;
    jittered.jitter = 0.45;
    jittered.linear = random_rotation_scale(rng);
    grid("jittered", jittered, true);
    for (double twist : {0.0, 0.8}) {
        PrismStackOptions o;
        o.seed = seed;
        o.layers = 2 + static_cast<int>(seed % 2);
        o.twist = twist;
        std::size_t boundary = 0;
        UnstructuredMesh mesh = make_prism_stack(o, &boundary);
        cases.push_back(
            {twist == 0 ? "prisms" : "twisted prisms", std::move(mesh), boundary, twist > 0});
    }
    for (Case& c : cases) {
        std::vector<double> ids(c.mesh.num_cells());
        for (std::size_t i = 0; i < ids.size(); ++i) ids[i] = static_cast<double>(i);
        c.mesh.cell_fields.push_back(make_double_field("cell", 1, ids));
    }
    return cases;
}

// Face adjacency of `mesh` has exactly `boundary_triangles` unshared faces (no cracks, no
// T-junctions), and neighbours are symmetric and share their three points.
void expect_conforming(const TetMesh& mesh, std::size_t boundary_triangles) {
    auto adjacency = build_face_adjacency(mesh);
    ASSERT_TRUE(adjacency.ok()) << adjacency.error().to_string();
    EXPECT_EQ(adjacency->boundary_faces.size(), boundary_triangles);
    for (CellId t = 0; t < mesh.num_tets(); ++t) {
        for (int k = 0; k < 4; ++k) {
            const CellId n = adjacency->neighbors[t][k];
            if (n == kNoCell) continue;
            int back = -1;
            for (int m = 0; m < 4; ++m) {
                if (adjacency->neighbors[n][m] == t) back = m;
            }
            ASSERT_GE(back, 0);
            auto f = face_points(mesh, t, k);
            auto g = face_points(mesh, n, back);
            std::sort(f.begin(), f.end());
            std::sort(g.begin(), g.end());
            ASSERT_EQ(f, g);
        }
    }
}

TEST(Tetrahedralize, QuadsAreCutThroughTheirLexicographicallySmallestPoint) {
    // A unit cube numbered so that index order and coordinate order disagree: the smallest
    // index is (1, 1, 1), the lexicographically smallest point (0, 0, 0) has index 6.
    UnstructuredMesh m;
    m.points = {{1, 1, 1}, {0, 1, 1}, {0, 0, 1}, {1, 0, 1},
                {1, 1, 0}, {0, 1, 0}, {0, 0, 0}, {1, 0, 0}};
    m.add_cell(CellType::kHexahedron, {6, 7, 4, 5, 2, 3, 0, 1});
    auto mesh = tetrahedralize(m);
    ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
    ASSERT_EQ(mesh->num_tets(), 6u);
    auto has_edge = [&](const Vec3& a, const Vec3& b) {
        for (CellId t = 0; t < mesh->num_tets(); ++t) {
            int found = 0;
            for (PointId p : mesh->tet(t)) found += mesh->point(p) == a || mesh->point(p) == b;
            if (found == 2) return true;
        }
        return false;
    };
    // The cone's apex is (0, 0, 0): in every tet.
    for (CellId t = 0; t < mesh->num_tets(); ++t) {
        int apex = 0;
        for (PointId p : mesh->tet(t)) apex += mesh->point(p) == Vec3(0, 0, 0);
        EXPECT_EQ(apex, 1) << "tet " << t;
    }
    // The three faces away from it: diagonals through their smallest point.
    EXPECT_TRUE(has_edge({1, 0, 0}, {1, 1, 1}));  // x = 1: smallest (1, 0, 0)
    EXPECT_FALSE(has_edge({1, 1, 0}, {1, 0, 1}));
    EXPECT_TRUE(has_edge({0, 1, 0}, {1, 1, 1}));  // y = 1: smallest (0, 1, 0)
    EXPECT_FALSE(has_edge({1, 1, 0}, {0, 1, 1}));
    EXPECT_TRUE(has_edge({0, 0, 1}, {1, 1, 1}));  // z = 1: smallest (0, 0, 1)
    EXPECT_FALSE(has_edge({1, 0, 1}, {0, 1, 1}));
}

TEST(Tetrahedralize, EveryCellTypeIsConformingIncludingTangledCells) {
    std::map<std::string, std::size_t> tangled;
    for (std::uint32_t seed = 1; seed <= 6; ++seed) {
        SCOPED_TRACE(seed);
        for (const Case& c : corpus(seed)) {
            SCOPED_TRACE(c.name);
            TetrahedralizeReport report;
            auto mesh = tetrahedralize(c.mesh, {}, &report);
            ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
            EXPECT_EQ(report.num_degenerate_tets, 0u);
            EXPECT_EQ(report.num_degenerate_cells, 0u);
            if (!c.tangled) {
                EXPECT_EQ(report.num_tangled_cells, 0u);
            }
            tangled[c.name] += report.num_tangled_cells;
            expect_conforming(*mesh, c.boundary_triangles);
        }
    }
    // The tangled cases do hold tangled cells (coned from a corner that cannot see them whole),
    // and stay conforming.
    for (const auto& [name, count] : tangled)
        std::printf("[ %s ] %zu tangled cells\n", name.c_str(), count);
    EXPECT_GT(tangled["jittered"], 0u);
    EXPECT_GT(tangled["twisted prisms"], 0u);
}

TEST(Tetrahedralize, TetsDoNotDependOnNumbering) {
    for (std::uint32_t seed = 1; seed <= 6; ++seed) {
        SCOPED_TRACE(seed);
        for (const Case& c : corpus(seed)) {
            SCOPED_TRACE(c.name);
            TetrahedralizeReport report;
            auto whole = tetrahedralize(c.mesh, {}, &report);
            ASSERT_TRUE(whole.ok()) << whole.error().to_string();
            const std::vector<CoordinateTet> expected = coordinate_tets(*whole);
            for (std::uint32_t shuffle = 0; shuffle < 3; ++shuffle) {
                SCOPED_TRACE(shuffle);
                const UnstructuredMesh renumbered = shuffle_mesh(c.mesh, 1000 * seed + shuffle);
                TetrahedralizeReport renumbered_report;
                auto tets = tetrahedralize(renumbered, {}, &renumbered_report);
                ASSERT_TRUE(tets.ok()) << tets.error().to_string();
                EXPECT_EQ(count_differences(coordinate_tets(*tets), expected), 0u);
                EXPECT_EQ(renumbered_report.num_tangled_cells, report.num_tangled_cells);
                EXPECT_EQ(renumbered_report.num_inverted_cells, report.num_inverted_cells);
                EXPECT_EQ(renumbered_report.num_tets, report.num_tets);
            }
            // Without merging the order holds as well, where no two points coincide.
            if (c.name != "duplicated points" && c.name != "quadratic") {
                TetrahedralizeOptions no_merge;
                no_merge.merge_points = false;
                auto unmerged = tetrahedralize(shuffle_mesh(c.mesh, seed), no_merge);
                ASSERT_TRUE(unmerged.ok());
                EXPECT_EQ(count_differences(coordinate_tets(*unmerged), expected), 0u);
            }
        }
    }
}

TEST(Tetrahedralize, PiecesSplitAloneGiveTheWholeMeshsTets) {
    for (std::uint32_t seed = 1; seed <= 6; ++seed) {
        SCOPED_TRACE(seed);
        for (const Case& c : corpus(seed)) {
            SCOPED_TRACE(c.name);
            auto whole = tetrahedralize(c.mesh);
            ASSERT_TRUE(whole.ok()) << whole.error().to_string();
            const std::vector<CoordinateTet> expected = coordinate_tets(*whole);
            const std::size_t num_pieces = 2 + seed % 3;
            // Slabs along a direction (as a .pvtu's pieces lie), or cells dealt at random (every
            // face a cut).
            std::mt19937 rng(seed);
            const Vec3 direction = glm::normalize(Vec3(1.0, 0.3 * seed, -0.2 * seed));
            std::vector<double> depth(c.mesh.num_cells());
            for (std::size_t cell = 0; cell < depth.size(); ++cell) {
                for (std::int64_t k = c.mesh.offsets[cell];
                     k < c.mesh.offsets[cell] + cell_corner_count(c.mesh.types[cell]); ++k) {
                    depth[cell] += glm::dot(c.mesh.points[c.mesh.connectivity[k]], direction);
                }
            }
            std::vector<double> sorted_depth = depth;
            std::sort(sorted_depth.begin(), sorted_depth.end());
            for (bool slabs : {true, false}) {
                SCOPED_TRACE(slabs ? "slabs" : "random");
                std::vector<std::vector<std::size_t>> pieces(num_pieces);
                for (std::size_t cell = 0; cell < depth.size(); ++cell) {
                    std::size_t piece = rng() % num_pieces;
                    if (slabs) {
                        const auto rank = static_cast<std::size_t>(
                            std::lower_bound(sorted_depth.begin(), sorted_depth.end(),
                                             depth[cell]) -
                            sorted_depth.begin());
                        piece = rank * num_pieces / depth.size();
                    }
                    pieces[piece].push_back(cell);
                }
                std::vector<CoordinateTet> joined;
                std::size_t shared_points = 0;
                std::set<std::array<double, 3>> seen;
                for (std::size_t i = 0; i < num_pieces; ++i) {
                    if (pieces[i].empty()) continue;
                    const UnstructuredMesh piece = extract_cells(c.mesh, pieces[i], seed + 17 * i);
                    auto tets = tetrahedralize(piece);
                    ASSERT_TRUE(tets.ok()) << tets.error().to_string();
                    for (PointId p = 0; p < tets->num_points(); ++p) {
                        const Vec3& q = tets->point(p);
                        shared_points += !seen.insert({q.x, q.y, q.z}).second;
                    }
                    const std::vector<CoordinateTet> part = coordinate_tets(*tets);
                    joined.insert(joined.end(), part.begin(), part.end());
                }
                std::sort(joined.begin(), joined.end());
                EXPECT_GT(shared_points, 0u);  // the pieces do touch
                EXPECT_EQ(count_differences(joined, expected), 0u);
            }
        }
    }
}

}  // namespace
}  // namespace tr
