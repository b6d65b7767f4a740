#include <tests/mesh/mixed_grid.h>

#include <algorithm>
#include <numeric>
#include <random>
#include <vector>

namespace tr::testing {

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
                        // Diagonal through the quad's smallest global id, as tetrahedralize
                        // does for the neighbours.
                        int s = 0;
                        for (int m = 1; m < 4; ++m) {
                            if (relabel[v[q[m]]] < relabel[v[q[s]]]) s = m;
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

}  // namespace tr::testing
