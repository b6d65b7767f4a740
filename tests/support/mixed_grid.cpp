#include <mesh/cell_type.h>
#include <mesh/tetrahedralize.h>
#include <tests/support/mixed_grid.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <vector>

namespace tr::testing {
namespace {

bool lexicographically_less(const Vec3& p, const Vec3& q) {
    if (p.x != q.x) return p.x < q.x;
    if (p.y != q.y) return p.y < q.y;
    return p.z < q.z;
}

CellType quadratic_type(CellType type) {
    switch (type) {
        case CellType::kTetra:
            return CellType::kQuadraticTetra;
        case CellType::kHexahedron:
            return CellType::kQuadraticHexahedron;
        case CellType::kWedge:
            return CellType::kQuadraticWedge;
        case CellType::kPyramid:
            return CellType::kQuadraticPyramid;
        default:
            return type;
    }
}

// Tuples `order[i]` of `field`, in that order.
Field gather(const Field& field, const std::vector<std::size_t>& order) {
    Field out = field;
    const auto nc = static_cast<std::size_t>(field.num_components);
    std::visit(
        [&](auto& dst) {
            const auto& src = std::get<std::decay_t<decltype(dst)>>(field.values);
            dst.resize(order.size() * nc);
            for (std::size_t i = 0; i < order.size(); ++i) {
                for (std::size_t k = 0; k < nc; ++k) dst[i * nc + k] = src[order[i] * nc + k];
            }
        },
        out.values);
    return out;
}

}  // namespace

UnstructuredMesh make_mixed_grid(const MixedGridOptions& o, double* expected_volume) {
    std::mt19937 rng(o.seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const int px = o.nx + 1, py = o.ny + 1, pz = o.nz + 1;
    auto grid_id = [&](int i, int j, int k) { return (k * py + j) * px + i; };

    // Grid points, then one centre point per box (used by pyramid and tet boxes).
    std::vector<Vec3> points;
    for (int k = 0; k < pz; ++k)
        for (int j = 0; j < py; ++j)
            for (int i = 0; i < px; ++i) points.emplace_back(i, j, k);
    const int first_centre = static_cast<int>(points.size());
    for (int k = 0; k < o.nz; ++k)
        for (int j = 0; j < o.ny; ++j)
            for (int i = 0; i < o.nx; ++i) points.emplace_back(i + 0.5, j + 0.5, k + 0.5);
    auto centre_id = [&](int i, int j, int k) { return first_centre + (k * o.ny + j) * o.nx + i; };

    if (o.jitter > 0) {
        std::mt19937 jitter_rng(o.seed ^ 0x9e3779b9u);
        std::uniform_real_distribution<double> shift(-o.jitter, o.jitter);
        for (Vec3& p : points) p += Vec3(shift(jitter_rng), shift(jitter_rng), shift(jitter_rng));
    }

    std::vector<std::int64_t> relabel(points.size());
    std::iota(relabel.begin(), relabel.end(), 0);
    if (o.shuffle_points) std::shuffle(relabel.begin(), relabel.end(), rng);

    UnstructuredMesh mesh;
    mesh.points.resize(points.size());
    for (std::size_t p = 0; p < points.size(); ++p) {
        mesh.points[relabel[p]] = o.linear * points[p] + o.offset;
    }
    std::vector<bool> wedge_column(static_cast<std::size_t>(o.nx * o.ny));
    for (auto&& w : wedge_column) w = unit(rng) < o.p_wedge_column;

    std::size_t boxes = 0;
    auto add = [&](CellType type, std::vector<std::int64_t> ids) {
        for (auto& id : ids) id = relabel[id];
        if (o.quadratic) {
            type = quadratic_type(type);
            // Mid nodes (ignored by the split) halfway between consecutive corners.
            const std::size_t corners = ids.size();
            for (std::size_t m = corners; m < static_cast<std::size_t>(cell_node_count(type));
                 ++m) {
                const Vec3 mid =
                    0.5 * (mesh.points[ids[m % corners]] + mesh.points[ids[(m + 1) % corners]]);
                ids.push_back(static_cast<std::int64_t>(mesh.points.size()));
                mesh.points.push_back(mid);
            }
        } else if (o.voxels && type == CellType::kHexahedron) {
            type = CellType::kVoxel;
            ids = {ids[0], ids[1], ids[3], ids[2], ids[4], ids[5], ids[7], ids[6]};
        }
        mesh.add_cell(type, ids);
    };
    for (int k = 0; k < o.nz; ++k) {
        for (int j = 0; j < o.ny; ++j) {
            for (int i = 0; i < o.nx; ++i) {
                if (o.skip_box && o.skip_box(i, j, k)) continue;
                ++boxes;
                const std::int64_t v[8] = {grid_id(i, j, k),
                                           grid_id(i + 1, j, k),
                                           grid_id(i + 1, j + 1, k),
                                           grid_id(i, j + 1, k),
                                           grid_id(i, j, k + 1),
                                           grid_id(i + 1, j, k + 1),
                                           grid_id(i + 1, j + 1, k + 1),
                                           grid_id(i, j + 1, k + 1)};
                const double r = unit(rng);
                if (wedge_column[j * o.nx + i]) {
                    // Split by the vertical plane through v0-v2: wedges (0,1,2 | 4,5,6) and
                    // (0,2,3 | 4,6,7); VTK wedge order wants the bottom triangle clockwise
                    // seen from the top, so list it reversed.
                    add(CellType::kWedge, {v[0], v[2], v[1], v[4], v[6], v[5]});
                    add(CellType::kWedge, {v[0], v[3], v[2], v[4], v[7], v[6]});
                } else if (r < o.p_pyramids) {
                    const std::int64_t c = centre_id(i, j, k);
                    // Base quads counter-clockwise seen from the centre (apex).
                    add(CellType::kPyramid, {v[0], v[1], v[2], v[3], c});
                    add(CellType::kPyramid, {v[4], v[7], v[6], v[5], c});
                    add(CellType::kPyramid, {v[0], v[4], v[5], v[1], c});
                    add(CellType::kPyramid, {v[1], v[5], v[6], v[2], c});
                    add(CellType::kPyramid, {v[2], v[6], v[7], v[3], c});
                    add(CellType::kPyramid, {v[3], v[7], v[4], v[0], c});
                } else if (r < o.p_pyramids + o.p_tets) {
                    const std::int64_t c = centre_id(i, j, k);
                    const int quads[6][4] = {{0, 1, 2, 3}, {4, 7, 6, 5}, {0, 4, 5, 1},
                                             {1, 5, 6, 2}, {2, 6, 7, 3}, {3, 7, 4, 0}};
                    for (const auto& q : quads) {
                        // Diagonal through the quad's lexicographically smallest point (after
                        // the affine map), as tetrahedralize does for the neighbours.
                        int s = 0;
                        for (int m = 1; m < 4; ++m) {
                            if (lexicographically_less(mesh.points[relabel[v[q[m]]]],
                                                       mesh.points[relabel[v[q[s]]]])) {
                                s = m;
                            }
                        }
                        const std::int64_t a = v[q[s]], b = v[q[(s + 1) % 4]],
                                           d = v[q[(s + 2) % 4]], e = v[q[(s + 3) % 4]];
                        add(CellType::kTetra, {a, b, d, c});
                        add(CellType::kTetra, {a, d, e, c});
                    }
                } else {
                    add(CellType::kHexahedron, {v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7]});
                }
            }
        }
    }
    if (o.duplicate_points) {
        UnstructuredMesh split;
        split.offsets = mesh.offsets;
        split.types = mesh.types;
        for (std::int64_t id : mesh.connectivity) {
            split.connectivity.push_back(static_cast<std::int64_t>(split.points.size()));
            split.points.push_back(mesh.points[id]);
        }
        mesh = std::move(split);
    }
    if (expected_volume) *expected_volume = glm::determinant(o.linear) * static_cast<double>(boxes);
    return mesh;
}

std::size_t box_boundary_triangles(const MixedGridOptions& o) {
    return 4u * static_cast<std::size_t>(o.nx * o.ny + o.ny * o.nz + o.nx * o.nz);
}

glm::dmat3 random_rotation_scale(std::mt19937& rng) {
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    glm::dmat3 m;
    do {
        for (int c = 0; c < 3; ++c)
            for (int r = 0; r < 3; ++r) m[c][r] = (r == c ? 1.5 : 0.0) + 0.4 * u(rng);
    } while (glm::determinant(m) < 0.2);
    return m;
}

UnstructuredMesh make_prism_stack(const PrismStackOptions& o, std::size_t* boundary_triangles) {
    // The disc: rings of 6 (radius 1), 12 (radius 2 and 3, every 30 degrees) and 12 (radius 4,
    // offset by 15 degrees) points around z.
    std::vector<glm::dvec2> disc;
    auto ring = [&](int count, double radius, double offset_degrees) {
        const int first = static_cast<int>(disc.size());
        for (int i = 0; i < count; ++i) {
            const double a = (offset_degrees + 360.0 * i / count) * M_PI / 180.0;
            disc.emplace_back(radius * std::cos(a), radius * std::sin(a));
        }
        return first;
    };
    const int r1 = ring(6, 1.0, 0.0), r2 = ring(12, 2.0, 0.0), r3 = ring(12, 3.0, 0.0),
              r4 = ring(12, 4.0, 15.0);
    std::vector<std::vector<int>> polygons;
    polygons.push_back({r1, r1 + 1, r1 + 2, r1 + 3, r1 + 4, r1 + 5});
    for (int i = 0; i < 6; ++i) {
        polygons.push_back(
            {r1 + i, r2 + 2 * i, r2 + 2 * i + 1, r2 + (2 * i + 2) % 12, r1 + (i + 1) % 6});
    }
    for (int k = 0; k < 12; ++k) {
        polygons.push_back({r2 + k, r3 + k, r3 + (k + 1) % 12, r2 + (k + 1) % 12});
        polygons.push_back({r3 + k, r4 + k, r3 + (k + 1) % 12});
        polygons.push_back({r4 + k, r4 + (k + 1) % 12, r3 + (k + 1) % 12});
    }
    // Counter-clockwise seen from +z.
    for (std::vector<int>& poly : polygons) {
        double area = 0;
        for (std::size_t i = 0; i < poly.size(); ++i) {
            const glm::dvec2 p = disc[poly[i]], q = disc[poly[(i + 1) % poly.size()]];
            area += p.x * q.y - p.y * q.x;
        }
        if (area < 0) std::reverse(poly.begin(), poly.end());
    }

    const int per_layer = static_cast<int>(disc.size());
    std::vector<Vec3> points;
    for (int l = 0; l <= o.layers; ++l) {
        const double a = o.twist * l, c = std::cos(a), s = std::sin(a);
        for (const glm::dvec2& p : disc)
            points.emplace_back(c * p.x - s * p.y, s * p.x + c * p.y, l);
    }
    std::mt19937 rng(o.seed);
    std::vector<std::int64_t> relabel(points.size());
    std::iota(relabel.begin(), relabel.end(), 0);
    if (o.shuffle_points) std::shuffle(relabel.begin(), relabel.end(), rng);
    UnstructuredMesh mesh;
    mesh.points.resize(points.size());
    for (std::size_t p = 0; p < points.size(); ++p) mesh.points[relabel[p]] = points[p];

    std::size_t cap_triangles = 0;
    for (int l = 0; l < o.layers; ++l) {
        for (const std::vector<int>& poly : polygons) {
            const int n = static_cast<int>(poly.size());
            std::vector<std::int64_t> ids;
            // VTK: a wedge's bottom triangle is clockwise seen from above, the other prisms'
            // bottoms counter-clockwise.
            for (int layer : {l, l + 1}) {
                for (int i = 0; i < n; ++i) {
                    const int v = n == 3 ? poly[(n - i) % n] : poly[i];
                    ids.push_back(relabel[layer * per_layer + v]);
                }
            }
            const CellType type = n == 3   ? CellType::kWedge
                                  : n == 4 ? CellType::kHexahedron
                                  : n == 5 ? CellType::kPentagonalPrism
                                           : CellType::kHexagonalPrism;
            mesh.add_cell(type, ids);
            if (l == 0) cap_triangles += 2 * static_cast<std::size_t>(n - 2);
        }
    }
    if (boundary_triangles) *boundary_triangles = cap_triangles + 24u * o.layers;
    return mesh;
}

UnstructuredMesh extract_cells(const UnstructuredMesh& mesh, const std::vector<std::size_t>& cells,
                               std::uint32_t seed) {
    // Points in order of first use, then numbered at random.
    std::vector<std::int64_t> local(mesh.num_points(), -1);
    std::vector<std::size_t> used;
    for (std::size_t c : cells) {
        for (std::int64_t k = mesh.offsets[c]; k < mesh.offsets[c + 1]; ++k) {
            const std::int64_t p = mesh.connectivity[k];
            if (local[p] < 0) {
                local[p] = static_cast<std::int64_t>(used.size());
                used.push_back(static_cast<std::size_t>(p));
            }
        }
    }
    std::mt19937 rng(seed);
    std::vector<std::size_t> order = used;  // order[new id] = old id
    std::shuffle(order.begin(), order.end(), rng);
    for (std::size_t i = 0; i < order.size(); ++i) local[order[i]] = static_cast<std::int64_t>(i);

    UnstructuredMesh piece;
    piece.points.reserve(order.size());
    for (std::size_t p : order) piece.points.push_back(mesh.points[p]);
    for (std::size_t c : cells) {
        std::vector<std::int64_t> ids(mesh.connectivity.begin() + mesh.offsets[c],
                                      mesh.connectivity.begin() + mesh.offsets[c + 1]);
        for (std::int64_t& id : ids) id = local[id];
        piece.add_cell(mesh.types[c], ids);
    }
    for (const Field& f : mesh.point_fields) piece.point_fields.push_back(gather(f, order));
    for (const Field& f : mesh.cell_fields) piece.cell_fields.push_back(gather(f, cells));
    return piece;
}

UnstructuredMesh shuffle_mesh(const UnstructuredMesh& mesh, std::uint32_t seed) {
    std::vector<std::size_t> cells(mesh.num_cells());
    std::iota(cells.begin(), cells.end(), std::size_t{0});
    std::mt19937 rng(seed);
    std::shuffle(cells.begin(), cells.end(), rng);
    return extract_cells(mesh, cells, seed + 1);
}

std::shared_ptr<const TetMesh> wavy_grid(const Vec3& offset) {
    MixedGridOptions o;
    o.nx = o.ny = o.nz = 3;
    o.offset = offset;
    TetMesh mesh = tetrahedralize(make_mixed_grid(o)).value();
    std::vector<double> wave;
    for (const Vec3& p : mesh.points()) {
        wave.push_back(0.5 + 0.45 * std::sin(1.3 * p.x) * std::cos(0.9 * p.y + 0.4 * p.z));
    }
    if (!mesh.add_point_field(make_double_field("wave", 1, std::move(wave))).ok()) return nullptr;
    return std::make_shared<const TetMesh>(std::move(mesh));
}

}  // namespace tr::testing
