#pragma once
// The scene the particle-based alpha tests share (header-only): a box [0, 3]^3 whose scalar runs
// with x from 0 to 1 and whose opacity ramps from none (x = 0) to opaque (x = 3), optionally a
// faint second volume [0, 2]^3 in the same space (fused), seen nearly down z so that the ray
// through (2.7, 1.5, 1.5) crosses the box where it is opaque (optical depth above 14), with
// empty margins; and a tilted opaque plane through them, drawn over a grey background.

#include <core/camera.h>
#include <mesh/surface_mesh.h>
#include <project/cpu_renderer.h>
#include <project/opaque_geometry.h>
#include <project/segment_shader.h>
#include <project/volume_scene.h>
#include <tests/pbvr/pbvr_test_scenes.h>

#include <cstddef>
#include <vector>

namespace tr::testing {

struct PbvrAlphaScene {
    TetMesh a_mesh = uniform_box(3, 3.0);
    TetMesh b_mesh = uniform_box(2, 2.0);
    std::vector<float> a_scalar = [this] {
        std::vector<float> s;
        for (const Vec3& p : a_mesh.points()) s.push_back(static_cast<float>(p.x / 3.0));
        return s;
    }();
    std::vector<float> b_scalar = std::vector<float>(b_mesh.num_points(), 0.5f);
    TransferFunction a_tf =
        TransferFunction::create({{0.0, {0.1, 0.2, 0.9}}, {1.0, {0.9, 0.3, 0.1}}},
                                 {{0.0, 0.0}, {0.5, 0.1}, {1.0, 0.95}}, 0.25)
            .value();
    TransferFunction b_tf =
        TransferFunction::create({{0.0, {0.2, 0.9, 0.3}}}, {{0.0, 0.1}}, 1.0).value();
    SegmentShader a_shader{a_tf, Integrator::kPreintegrated, longest_edge(a_mesh)};
    CameraFrame frame{camera_at({3.5, 2.5, 14}, {1.5, 1.5, 1.5}, false, 30), 64, 64};
    SurfaceMesh plane = [] {
        SurfaceMesh p;  // z = 0.5 + 0.3 x
        p.points = {{-1, -1, 0.2}, {4, -1, 1.7}, {4, 4, 1.7}, {-1, 4, 0.2}};
        p.triangles = {{0, 1, 2}, {0, 2, 3}};
        return p;
    }();
    OpaqueLayer layer = render_opaque({{&plane, Vec3(0.2, 0.9, 0.3)}}, frame, Vec3(0.4, 0.35, 0.3));

    // With `shader`, the box's shader is given (image-space PBVR then takes each segment's mean
    // colour); with `fused`, the second volume is drawn too.
    VolumeScene scene(const Vec3& background, bool opaque_depth, bool opaque_color, bool shader,
                      bool fused) const {
        VolumeScene s;
        s.volumes.push_back({&a_mesh, a_scalar, &a_tf, shader ? &a_shader : nullptr});
        if (fused) s.volumes.push_back({&b_mesh, b_scalar, &b_tf, nullptr});
        s.camera = &frame;
        s.background = background;
        if (opaque_depth) s.opaque_depth = &layer.depth;
        if (opaque_color) s.opaque_color = &layer.color;
        return s;
    }

    // The pixel of the ray through (2.7, 1.5, 1.5): nearly opaque.
    std::size_t opaque_pixel() const {
        const Vec3 q = frame.project(Vec3(2.7, 1.5, 1.5));
        return static_cast<std::size_t>(q.y) * frame.width() + static_cast<std::size_t>(q.x);
    }
};

}  // namespace tr::testing
