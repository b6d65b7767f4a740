#include <pipeline/pipeline.h>
#include <pipeline/scene.h>
#include <tests/viewer/viewer_fixtures.h>

#include <gtest/gtest.h>

#include <fstream>
#include <vector>

namespace tr::testing {

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
