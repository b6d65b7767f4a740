#include <io/write_vtu.h>
#include <mesh/point_data.h>
#include <project/opaque_geometry.h>
#include <tests/apps/cli_runner.h>
#include <tests/viewer/viewer_fixtures.h>
#include <tests/viewer/viewer_test_scene.h>

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <vector>

namespace tr::testing {

std::string write_test_scene_variant(const TestScene& t, const std::string& name,
                                     const std::string& opacity, const std::string& method) {
    const std::string path = t.dir + "/" + name;
    std::ofstream scene(path);
    scene << R"({
  "mesh": "cube.vtu",
  "scalar": "blob",
  "transfer_function": {
    "color": [[-0.25, 0.1, 0.2, 0.9], [0.5, 0.2, 0.9, 0.4], [1.2, 1.0, 0.6, 0.1]],
    "opacity": )"
          << opacity << R"(,
    "unit_distance": 0.4
  },
  "camera": {"position": [2.6, -3.4, 2.0], "focal_point": [0, 0, 0], "view_up": [0, 0, 1],
             "view_angle": 35},
  "image": {"width": 240, "height": 180, "background": [0.05, 0.05, 0.08]},)"
          << (method.empty() ? "" : "\n  \"method\": " + method + ",") << R"(
  "opaque": [{"file": "cylinder.off", "color": [0.9, 0.8, 0.7]}]
})";
    return path;
}

TestScene make_test_scene(int n, const std::string& opacity, const std::string& method) {
    TestScene t;
    TetMesh mesh = freudenthal_box(n, n, n, Vec3(-1.0), Vec3(1.0));
    std::vector<float> blob;
    for (const Vec3& p : mesh.points()) {
        const double r2 = glm::dot(p - Vec3(0.2, -0.1, 0.1), p - Vec3(0.2, -0.1, 0.1));
        blob.push_back(static_cast<float>(std::exp(-2.0 * r2) + 0.25 * std::sin(3 * p.x)));
    }
    EXPECT_TRUE(mesh.add_point_field(make_float_field("blob", 1, blob)).ok());
    t.mesh = t.dir + "/cube.vtu";
    EXPECT_TRUE(write_vtu(mesh, t.mesh).ok());
    const SurfaceMesh cylinder = make_cylinder_surface(0.3, -0.6, 0.6, 24);
    t.cylinder = t.dir + "/cylinder.off";
    write_off(cylinder, t.cylinder);
    t.scene = write_test_scene_variant(t, "scene.json", opacity, method);
    return t;
}

}  // namespace tr::testing
