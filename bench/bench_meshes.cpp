#include <bench/bench_meshes.h>
#include <mesh/tetrahedralize.h>

#include <cmath>
#include <map>
#include <memory>

namespace tr::bench {

UnstructuredMesh hex_grid(int n, bool hole) {
    UnstructuredMesh m;
    const int p = n + 1;
    m.points.reserve(static_cast<std::size_t>(p) * p * p);
    for (int k = 0; k < p; ++k)
        for (int j = 0; j < p; ++j)
            for (int i = 0; i < p; ++i) m.points.emplace_back(i, j, k + 0.001 * ((i * j) % 7));
    auto id = [p](int i, int j, int k) { return static_cast<std::int64_t>((k * p + j) * p + i); };
    m.offsets.reserve(static_cast<std::size_t>(n) * n * n + 1);
    m.offsets.push_back(0);
    for (int k = 0; k < n; ++k) {
        for (int j = 0; j < n; ++j) {
            for (int i = 0; i < n; ++i) {
                if (hole && i >= n / 3 && i < 2 * n / 3 && j >= n / 3 && j < 2 * n / 3) continue;
                const std::int64_t v[8] = {id(i, j, k),
                                           id(i + 1, j, k),
                                           id(i + 1, j + 1, k),
                                           id(i, j + 1, k),
                                           id(i, j, k + 1),
                                           id(i + 1, j, k + 1),
                                           id(i + 1, j + 1, k + 1),
                                           id(i, j + 1, k + 1)};
                m.connectivity.insert(m.connectivity.end(), v, v + 8);
                m.offsets.push_back(static_cast<std::int64_t>(m.connectivity.size()));
                m.types.push_back(CellType::kHexahedron);
            }
        }
    }
    return m;
}

const TetMesh& tet_grid(int n, bool hole) {
    static std::map<std::pair<int, bool>, std::unique_ptr<TetMesh>> cache;
    auto& slot = cache[{n, hole}];
    if (!slot) {
        auto mesh = tetrahedralize(hex_grid(n, hole));
        slot = std::make_unique<TetMesh>(std::move(mesh).value());
        std::vector<float> scalar(slot->num_points());
        for (std::size_t i = 0; i < scalar.size(); ++i) scalar[i] = static_cast<float>(i % 97);
        (void)slot->add_point_field(make_float_field("scalar", 1, std::move(scalar)));
    }
    return *slot;
}

int grid_size_for(double tets) { return static_cast<int>(std::lround(std::cbrt(tets / 6.0))); }

}  // namespace tr::bench
