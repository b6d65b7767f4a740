#pragma once
// The tests' structured box of tets (the viewer's scenes, the particle and splat tests' uniform
// box): a grid of cells, each split into the 6 tets of the Freudenthal (Kuhn) split.
// Header-only: any target linking tetrender::mesh can use it.

#include <mesh/tet_mesh.h>

#include <vector>

namespace tr::testing {

// The box [lo, hi] as an nx x ny x nz grid of cells, each split into 6 tets around its main
// diagonal (the paths from corner (0, 0, 0) to (1, 1, 1) one axis at a time: conforming across
// cells), points numbered x fastest, point (i, j, k) at lo + (i, j, k) * (hi - lo) / (nx, ny,
// nz). No fields. Preconditions: nx, ny, nz >= 1 and lo < hi.
inline TetMesh freudenthal_box(int nx, int ny, int nz, const Vec3& lo, const Vec3& hi) {
    std::vector<Vec3> points;
    auto id = [&](int i, int j, int k) {
        return static_cast<PointId>((k * (ny + 1) + j) * (nx + 1) + i);
    };
    const Vec3 step = (hi - lo) / Vec3(nx, ny, nz);
    for (int k = 0; k <= nz; ++k) {
        for (int j = 0; j <= ny; ++j) {
            for (int i = 0; i <= nx; ++i) points.push_back(lo + Vec3(i, j, k) * step);
        }
    }
    std::vector<Tet> tets;
    const int paths[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
    for (int k = 0; k < nz; ++k) {
        for (int j = 0; j < ny; ++j) {
            for (int i = 0; i < nx; ++i) {
                for (const auto& path : paths) {
                    int c[3] = {i, j, k};
                    Tet tet;
                    tet[0] = id(c[0], c[1], c[2]);
                    for (int s = 0; s < 3; ++s) {
                        ++c[path[s]];
                        tet[s + 1] = id(c[0], c[1], c[2]);
                    }
                    tets.push_back(tet);
                }
            }
        }
    }
    return TetMesh::create(std::move(points), std::move(tets)).value();
}

}  // namespace tr::testing
