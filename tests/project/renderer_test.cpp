// The CPU renderer: seams, accuracy of each integrator against the reference ray caster,
// thread determinism, the camera inside the mesh.
#include <core/parallel.h>
#include <mesh/face_adjacency.h>
#include <mesh/tetrahedralize.h>
#include <project/cpu_renderer.h>
#include <project/opaque_geometry.h>
#include <project/reference_raycaster.h>
#include <sort/visibility_sort.h>
#include <tests/mesh/mixed_grid.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>

namespace tr {
namespace {

using testing::make_mixed_grid;
using testing::MixedGridOptions;

struct Fixture {
    TetMesh mesh;
    FaceAdjacency adjacency;
    std::vector<float> scalar;
};

// A mixed grid over [0, n]^3 (no shuffled numbering needed) with scalar f(x, y, z).
Fixture make_fixture(int n, float (*f)(const Vec3&), std::uint32_t seed = 1) {
    MixedGridOptions o;
    o.nx = o.ny = o.nz = n;
    o.seed = seed;
    Fixture fx;
    fx.mesh = tetrahedralize(make_mixed_grid(o)).value();
    fx.adjacency = build_face_adjacency(fx.mesh).value();
    for (const Vec3& p : fx.mesh.points()) fx.scalar.push_back(f(p));
    return fx;
}

Image render(const Fixture& fx, const TransferFunction& tf, const CameraFrame& frame,
             Integrator integrator, const Vec3& background, RenderStats* stats = nullptr) {
    VisibilitySorter sorter;
    std::vector<CellId> order;
    sorter.sort(fx.mesh, fx.adjacency, SortView::from_camera(frame), SortMethod::kMpvo, order);
    const SegmentShader shader(tf, integrator, longest_edge(fx.mesh));
    RenderInputs in;
    in.mesh = &fx.mesh;
    in.scalar = fx.scalar;
    in.order = order;
    in.shader = &shader;
    in.camera = &frame;
    in.background = background;
    return render_projected_tetrahedra(in, stats);
}

Camera looking_at(const Vec3& eye, const Vec3& focal, bool parallel, double scale) {
    Camera c;
    c.position = eye;
    c.focal_point = focal;
    c.view_up = std::abs(glm::normalize(focal - eye).z) > 0.9 ? Vec3(0, 1, 0) : Vec3(0, 0, 1);
    c.parallel = parallel;
    c.parallel_scale = scale;
    c.view_angle = 40;
    return c;
}

// Length of a ray inside the box [0, n]^3 (slab test).
double box_chord(const Ray& r, double n) {
    double t0 = 0, t1 = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3; ++a) {
        if (r.direction[a] == 0) {
            if (r.origin[a] < 0 || r.origin[a] > n) return 0;
            continue;
        }
        double ta = (0 - r.origin[a]) / r.direction[a], tb = (n - r.origin[a]) / r.direction[a];
        if (ta > tb) std::swap(ta, tb);
        t0 = std::max(t0, ta), t1 = std::min(t1, tb);
    }
    return std::max(0.0, t1 - t0);
}

TEST(Renderer, UniformCubeHasNoSeams) {
    const Fixture fx = make_fixture(3, [](const Vec3&) { return 1.0f; });
    const TransferFunction tf =
        TransferFunction::create({{1, {1.0, 0.7, 0.2}}}, {{1, 0.35}}, 1.0).value();
    const double kappa = tf.extinction(1.0);
    const Vec3 background(0.05, 0.1, 0.2);
    const Camera cameras[] = {
        looking_at({1.5, 1.5, 12}, {1.5, 1.5, 1.5}, true, 2.2),  // straight down an axis
        looking_at({7, -5, 6}, {1.5, 1.5, 1.5}, false, 1),       // perspective, oblique
        looking_at({-4, 1.5, 1.5}, {1.5, 1.5, 1.5}, false, 1),   // eye on grid planes
        looking_at({5, 5, 5}, {1.5, 1.5, 1.5}, true, 2.8),       // along the diagonal
    };
    for (Integrator integrator :
         {Integrator::kExact, Integrator::kPreintegrated, Integrator::kExpTexture}) {
        for (const Camera& c : cameras) {
            // exp-texture interpolates thickness linearly across each cell's projected
            // triangles, as the paper does: exact under orthographic projection only (its
            // perspective accuracy is measured against the reference below).
            if (integrator == Integrator::kExpTexture && !c.parallel) continue;
            const CameraFrame frame(c, 64, 64);
            const Image image = render(fx, tf, frame, integrator, background);
            int covered = 0;
            for (int j = 0; j < 64; ++j) {
                for (int i = 0; i < 64; ++i) {
                    const double chord = box_chord(frame.pixel_ray(i, j), 3.0);
                    const double alpha = 1 - std::exp(-kappa * chord);
                    const Vec3 expected = Vec3(1.0, 0.7, 0.2) * alpha + (1 - alpha) * background;
                    covered += chord > 0;
                    const double tolerance = 1.0 / 255;
                    for (int k = 0; k < 3; ++k) {
                        ASSERT_NEAR(image.at(i, j)[k], expected[k], tolerance)
                            << integrator_name(integrator) << " camera " << (&c - cameras)
                            << " pixel " << i << "," << j;
                    }
                }
            }
            EXPECT_GT(covered, 500);
        }
    }
}

float wavy(const Vec3& p) {
    return static_cast<float>(0.5 + 0.45 * std::sin(1.3 * p.x) * std::cos(0.9 * p.y + 0.4 * p.z));
}

TransferFunction wavy_tf() {
    return TransferFunction::create({{0.0, {0.1, 0.2, 0.9}},
                                     {0.4, {0.2, 0.9, 0.4}},
                                     {0.7, {0.95, 0.8, 0.1}},
                                     {1.0, {0.9, 0.1, 0.1}}},
                                    {{0.0, 0.0}, {0.3, 0.05}, {0.6, 0.4}, {1.0, 0.8}}, 1.5)
        .value();
}

TEST(Renderer, IntegratorsAgainstTheReference) {
    const Fixture fx = make_fixture(4, wavy, 3);
    const TransferFunction tf = wavy_tf();
    const Vec3 background(0.0);
    const Camera cameras[] = {looking_at({9, -6, 7}, {2, 2, 2}, false, 1),
                              looking_at({-3, 8, 1}, {2, 2, 2}, true, 3.6)};
    const double required[] = {45, 45, 36};  // exact, preintegrated, exp-texture
    for (const Camera& c : cameras) {
        const CameraFrame frame(c, 512, 512);  // the size
        const Image reference = render_reference(fx.mesh, fx.scalar, tf, frame, background);
        int n = 0;
        for (Integrator integrator :
             {Integrator::kExact, Integrator::kPreintegrated, Integrator::kExpTexture}) {
            const Image image = render(fx, tf, frame, integrator, background);
            const double db = psnr(image, reference);
            std::printf("[ %s %s ] PSNR %.1f dB, max diff %.4f\n", c.parallel ? "ortho" : "persp",
                        std::string(integrator_name(integrator)).c_str(), db,
                        max_abs_difference(image, reference));
            EXPECT_GE(db, required[n++]) << integrator_name(integrator);
        }
    }
}

TEST(Renderer, CameraInsideTheMesh) {
    const Fixture fx = make_fixture(4, wavy, 5);
    const TransferFunction tf = wavy_tf();
    Camera c = looking_at({1.3, 1.7, 2.2}, {4, 3, 2.5}, false, 1);
    c.view_angle = 80;
    const CameraFrame frame(c, 96, 96);
    const Image reference = render_reference(fx.mesh, fx.scalar, tf, frame, Vec3(0.0));
    const Image image = render(fx, tf, frame, Integrator::kExact, Vec3(0.0));
    EXPECT_GE(psnr(image, reference), 45.0);
}

TEST(Renderer, BitIdenticalWhateverTheThreadCount) {
    const Fixture fx = make_fixture(4, wavy, 7);
    const TransferFunction tf = wavy_tf();
    const CameraFrame frame(looking_at({8, -5, 6}, {2, 2, 2}, false, 1), 150, 110);
    set_thread_count(1);
    const Image one = render(fx, tf, frame, Integrator::kPreintegrated, Vec3(0.1));
    set_thread_count(2);
    const Image two = render(fx, tf, frame, Integrator::kPreintegrated, Vec3(0.1));
    set_thread_count(7);
    const Image seven = render(fx, tf, frame, Integrator::kPreintegrated, Vec3(0.1));
    set_thread_count(0);
    EXPECT_EQ(std::memcmp(one.pixels.data(), two.pixels.data(), one.pixels.size() * sizeof(Vec3f)),
              0);
    EXPECT_EQ(
        std::memcmp(one.pixels.data(), seven.pixels.data(), one.pixels.size() * sizeof(Vec3f)), 0);
}

TEST(Renderer, OpaqueGeometryCutsEverySegmentAtItsDepth) {
    const Fixture fx = make_fixture(3, [](const Vec3&) { return 1.0f; });
    const TransferFunction tf =
        TransferFunction::create({{1, {1.0, 0.7, 0.2}}}, {{1, 0.35}}, 1.0).value();
    const double kappa = tf.extinction(1.0);
    // A tilted plane through the cube: z = 1 + 0.3 x, seen from above.
    SurfaceMesh plane;
    plane.points = {{-1, -1, 0.7}, {4, -1, 2.2}, {4, 4, 2.2}, {-1, 4, 0.7}};
    plane.triangles = {{0, 1, 2}, {0, 2, 3}};
    const Vec3 plane_color(0.2, 0.9, 0.3);
    for (bool parallel : {true, false}) {
        const CameraFrame frame(looking_at({1.5, 1.5, 12}, {1.5, 1.5, 1.5}, parallel, 2.2), 64, 64);
        const OpaqueLayer layer = render_opaque({{&plane, plane_color}}, frame, Vec3(0.0));
        EXPECT_GT(layer.pixels_covered, 1500u);
        VisibilitySorter sorter;
        std::vector<CellId> order;
        sorter.sort(fx.mesh, fx.adjacency, SortView::from_camera(frame), SortMethod::kMpvo, order);
        const SegmentShader shader(tf, Integrator::kExact, longest_edge(fx.mesh));
        RenderInputs in;
        in.mesh = &fx.mesh;
        in.scalar = fx.scalar;
        in.order = order;
        in.shader = &shader;
        in.camera = &frame;
        in.opaque_color = &layer.color;
        in.opaque_depth = &layer.depth;
        const Image image = render_projected_tetrahedra(in);
        const Vec3 normal = glm::normalize(Vec3(-0.3, 0, 1));
        for (int j = 0; j < 64; ++j) {
            for (int i = 0; i < 64; ++i) {
                const Ray r = frame.pixel_ray(i, j);
                // Where the ray meets the plane, and how much of the cube lies before it.
                const double t_plane =
                    glm::dot(normal, Vec3(0, 0, 1) - r.origin) / glm::dot(normal, r.direction);
                const Vec3 hit = r.origin + t_plane * r.direction;
                if (hit.x < 0.01 || hit.x > 2.99 || hit.y < 0.01 || hit.y > 2.99) continue;
                const double t_top = (3.0 - r.origin.z) / r.direction.z;
                const double chord = t_plane - t_top;
                const double alpha = 1 - std::exp(-kappa * chord);
                const double lambert = 0.2 + 0.8 * std::abs(glm::dot(normal, r.direction));
                const Vec3 expected =
                    Vec3(1.0, 0.7, 0.2) * alpha + (1 - alpha) * plane_color * lambert;
                for (int k = 0; k < 3; ++k) {
                    ASSERT_NEAR(image.at(i, j)[k], expected[k], 1.0 / 255) << i << "," << j;
                }
            }
        }
    }
}

}  // namespace
}  // namespace tr
