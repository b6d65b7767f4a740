#pragma once
// What the flowtex scene-method tests share: the fixture's flow mesh with a scalar, handed to a
// scene, a top view, and texture-advection's keys.

#include <mesh/field.h>
#include <pipeline/scene.h>
#include <tests/flowtex/fixtures.h>

#include <cstdlib>
#include <memory>

namespace tr::testing {

inline constexpr int kSize = 96;

// The fixture's mixed grid over [-2, 2]^3 with velocity (-y, x, 0) + (0.3, 0, 0) and the scalar
// s = z, handed to a scene.
inline std::shared_ptr<const TetMesh> flow_mesh() {
    static const std::shared_ptr<const TetMesh> mesh = [] {
        testing::MeshFixture f =
            mesh_with_field(glm::dmat3(0, 1, 0, -1, 0, 0, 0, 0, 0), Vec3(0.3, 0, 0));
        TetMesh m = f.mesh;
        if (!m.add_point_field(f.field).ok()) std::abort();
        std::vector<float> s;
        for (const Vec3& p : m.points()) s.push_back(static_cast<float>(p.z));
        if (!m.add_point_field(make_float_field("s", 1, s)).ok()) std::abort();
        return std::make_shared<const TetMesh>(std::move(m));
    }();
    return mesh;
}

// A scene of the flow mesh with a uniform medium: opacity `a` per unit length, black or white
// glow; a = 0: a clear volume.
inline Scene flow_scene(double a, double glow = 0.0) {
    Scene scene;
    SceneVolume v;
    v.mesh = "flow_mesh";
    v.tets = flow_mesh();
    v.scalar = "s";
    v.transfer_function =
        TransferFunction::create({{-2, Vec3(glow)}, {2, Vec3(glow)}}, {{-2, a}, {2, a}}, 1.0)
            .value();
    scene.volumes.push_back(v);
    scene.width = scene.height = kSize;
    scene.source = "flow.scene.json";
    return scene;
}

// Looking down -z (or up +z) at the origin, orthographic, [-2, 2]^2 in view.
inline Camera top_camera(bool from_above) {
    Camera c;
    c.parallel = true;
    c.parallel_scale = 2.2;
    c.focal_point = Vec3(0.0);
    c.position = Vec3(0, 0, from_above ? 10 : -10);
    c.view_up = Vec3(0, 1, 0);
    return c;
}

inline MethodSpec advection_method(const NumberLists& slices, int steps, double opacity) {
    MethodSpec m;
    m.name = "texture-advection";
    m.options["vectors"] = std::string("velocity");
    m.options["slices"] = slices;
    m.options["steps"] = std::int64_t{steps};
    m.options["resolution"] = std::int64_t{64};
    m.options["dt"] = 0.02;
    m.options["sheet_opacity"] = opacity;
    return m;
}

}  // namespace tr::testing
