#include <pipeline/pipeline.h>
#include <project/scene.h>
#include <tests/viewer/viewer_fixtures.h>

#include <gtest/gtest.h>

#include <fstream>
#include <vector>

namespace tr::testing {

TetMesh freudenthal_box(int nx, int ny, int nz, const Vec3& lo, const Vec3& hi) {
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
    auto mesh = TetMesh::create(std::move(points), std::move(tets));
    EXPECT_TRUE(mesh.ok());
    return std::move(mesh).value();
}

void write_off(const SurfaceMesh& surface, const std::string& path) {
    std::ofstream off(path);
    off << "OFF\n" << surface.points.size() << " " << surface.triangles.size() << " 0\n";
    for (const Vec3& p : surface.points) off << p.x << " " << p.y << " " << p.z << "\n";
    for (const auto& tri : surface.triangles) {
        off << "3 " << tri[0] << " " << tri[1] << " " << tri[2] << "\n";
    }
}

Image cpu_picture(const std::string& scene_path, Integrator integrator) {
    auto scene = read_scene(scene_path);
    EXPECT_TRUE(scene.ok());
    Pipeline pipeline;
    RenderOptions options;
    options.integrator = integrator;
    auto result = pipeline.render(*scene, options);
    EXPECT_TRUE(result.ok()) << result.error().to_string();
    return result.ok() ? std::move(result->image) : Image();
}

}  // namespace tr::testing
