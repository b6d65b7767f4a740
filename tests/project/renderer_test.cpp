// The CPU renderer: seams, accuracy of each integrator against the reference ray caster and of
// the default against the exact one (optically thin and thick cells), thread determinism, the
// camera inside the mesh, the alpha it gives for compositing, the preconditions it checks.
#include <core/config.h>
#include <core/parallel.h>
#include <mesh/face_adjacency.h>
#include <mesh/tetrahedralize.h>
#include <project/cpu_renderer.h>
#include <project/opaque_geometry.h>
#include <project/reference_raycaster.h>
#include <project/tet_fragments.h>
#include <sort/visibility_sort.h>
#include <tests/project/alpha_check.h>
#include <tests/support/image_check.h>
#include <tests/support/mixed_grid.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

namespace tr {
namespace {

using testing::ImageBounds;
using testing::images_match;
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

// The renderer's inputs for the fixture in `order` (which, with the shader and frame, must
// outlive them), over a black background.
RenderInputs inputs(const Fixture& fx, const SegmentShader& shader, const CameraFrame& frame,
                    const std::vector<CellId>& order) {
    RenderInputs in;
    in.mesh = &fx.mesh;
    in.scalar = fx.scalar;
    in.order = order;
    in.shader = &shader;
    in.camera = &frame;
    return in;
}

Image render(const Fixture& fx, const TransferFunction& tf, const CameraFrame& frame,
             Integrator integrator, const Vec3& background, RenderStats* stats = nullptr,
             std::vector<float>* alpha = nullptr) {
    VisibilitySorter sorter;
    std::vector<CellId> order;
    sorter.sort(fx.mesh, fx.adjacency, SortView::from_camera(frame), SortMethod::kMpvo, order);
    const SegmentShader shader(tf, integrator, longest_edge(fx.mesh));
    RenderInputs in = inputs(fx, shader, frame, order);
    in.background = background;
    return render_projected_tetrahedra(in, stats, alpha);
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
    // Per integrator, over all cameras (single precision is all that is left): at least 7 dB
    // under the lowest PSNR measured, the largest difference within 1e-5.
    const ImageBounds bounds[3] = {{110.0, 1e-5},   // kExpTexture: measured 117.5 dB, < 5e-6
                                   {138.0, 1e-5},   // kPreintegrated: measured 145.6 dB, < 5e-6
                                   {140.0, 1e-5}};  // kExact: measured 148.6 dB, < 5e-6
    for (Integrator integrator :
         {Integrator::kExact, Integrator::kPreintegrated, Integrator::kExpTexture}) {
        for (const Camera& c : cameras) {
            // exp-texture interpolates thickness linearly across each cell's projected
            // triangles, as the paper does: exact under orthographic projection only (its
            // perspective accuracy is measured against the reference below).
            if (integrator == Integrator::kExpTexture && !c.parallel) continue;
            const CameraFrame frame(c, 64, 64);
            const Image image = render(fx, tf, frame, integrator, background);
            Image expected(64, 64);
            int covered = 0;
            for (int j = 0; j < 64; ++j) {
                for (int i = 0; i < 64; ++i) {
                    const double chord = box_chord(frame.pixel_ray(i, j), 3.0);
                    const double alpha = 1 - std::exp(-kappa * chord);
                    expected.at(i, j) =
                        Vec3f(Vec3(1.0, 0.7, 0.2) * alpha + (1 - alpha) * background);
                    covered += chord > 0;
                }
            }
            const int n = static_cast<int>(integrator);
            EXPECT_TRUE(images_match(image, expected, Vec3f(background), bounds[n],
                                     std::string(integrator_name(integrator)) + "_uniform_cube_" +
                                         std::to_string(&c - cameras)));
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

// Renders with each integrator and compares against the reference ray caster (bounds in
// kExact, kPreintegrated, kExpTexture order), and the default against kExact: within one 8-bit
// level after rounding everywhere (the default is within half a level of exact).
void check_integrators(const Fixture& fx, const TransferFunction& tf, const CameraFrame& frame,
                       const std::string& name, const ImageBounds (&bounds)[3],
                       const ImageBounds& default_vs_exact) {
    const Vec3f background(0.0f);
    const Image reference = render_reference(fx.mesh, fx.scalar, tf, frame, Vec3(background));
    Image images[3];
    const Integrator integrators[3] = {Integrator::kExact, Integrator::kPreintegrated,
                                       Integrator::kExpTexture};
    for (int n = 0; n < 3; ++n) {
        images[n] = render(fx, tf, frame, integrators[n], Vec3(background));
        EXPECT_TRUE(images_match(images[n], reference, background, bounds[n],
                                 name + "_" + std::string(integrator_name(integrators[n]))));
    }
    EXPECT_TRUE(images_match(images[1], images[0], background, default_vs_exact,
                             name + "_default_vs_exact"));
    const ImageComparison c = compare_images(images[1], images[0], background);
    EXPECT_LE(c.max_levels, 1) << name;
    EXPECT_GT(c.foreground_pixels, static_cast<std::size_t>(frame.width()) * frame.height() / 8);
}

TEST(Renderer, IntegratorsAgainstTheReference) {
    const Fixture fx = make_fixture(4, wavy, 3);
    const TransferFunction tf = wavy_tf();
    // 512 x 512, the size.
    const CameraFrame persp(looking_at({9, -6, 7}, {2, 2, 2}, false, 1), 512, 512);
    const CameraFrame ortho(looking_at({-3, 8, 1}, {2, 2, 2}, true, 3.6), 512, 512);
    // Bounds: measured minus 3 dB, measured largest difference plus about a quarter level.
    check_integrators(fx, tf, persp, "wavy_persp",
                      {{88.0, 0.0006},  // measured 91.0 dB, 0.00014
                       {87.0, 0.0012},  // measured 90.9 dB, 0.00027
                       {45.5, 0.065}},  // measured 49.9 dB, 0.0544 (14 levels)
                      {83.0, 0.0015});  // measured 86.4 dB, 0.00038
    check_integrators(fx, tf, ortho, "wavy_ortho",
                      {{86.0, 0.0006},  // measured 88.4 dB, 0.00015
                       {86.5, 0.0012},  // measured 90.2 dB, 0.00031
                       {44.9, 0.04}},   // measured 49.5 dB, 0.0289 (7 levels)
                      {82.0, 0.0015});  // measured 85.3 dB, 0.00028
}

// Optically thick cells: opacity 0.6 to 0.99 per unit distance of 0.2, so a unit cell is five
// unit distances deep (optical depth 5 to 23 across it), with the scalar and the colour (11
// viridis control points) varying inside every cell.
TransferFunction thick_tf() {
    const double rgb[11][3] = {{0.267, 0.005, 0.329}, {0.283, 0.141, 0.458}, {0.254, 0.265, 0.53},
                               {0.207, 0.372, 0.553}, {0.164, 0.471, 0.558}, {0.128, 0.567, 0.551},
                               {0.135, 0.659, 0.518}, {0.267, 0.749, 0.441}, {0.478, 0.821, 0.318},
                               {0.741, 0.873, 0.15},  {0.993, 0.906, 0.144}};
    std::vector<ColorPoint> colors;
    for (int i = 0; i < 11; ++i)
        colors.push_back({i / 10.0, Vec3(rgb[i][0], rgb[i][1], rgb[i][2])});
    return TransferFunction::create(colors, {{0.0, 0.6}, {0.5, 0.95}, {1.0, 0.99}}, 0.2).value();
}

TEST(Renderer, OpticallyThickCellsAgainstTheReference) {
    const Fixture fx = make_fixture(3, wavy, 9);
    const TransferFunction tf = thick_tf();
    const CameraFrame persp(looking_at({7, -5, 6}, {1.5, 1.5, 1.5}, false, 1), 160, 160);
    const CameraFrame ortho(looking_at({-3, 6, 1}, {1.5, 1.5, 1.5}, true, 2.8), 160, 160);
    // The old (front, back, length) table: 45.0 and 46.5 dB, 29 and 24 levels off.
    // *exp-texture takes each tet's colour at its chord's mean scalar, so its error depends on
    // how the grid's cells are split into tets: measured over two splits.
    check_integrators(fx, tf, persp, "thick_persp",
                      {{120.0, 0.0002},  // measured 126.4 dB, 0.000002
                       {78.7, 0.0015},   // measured 81.8 dB, 0.00104
                       {27.9, 0.40}},    // measured 31.0-32.8 dB, 0.23-0.34 (87 levels)*
                      {78.7, 0.0015});   // measured 81.8 dB, 0.00104
    check_integrators(fx, tf, ortho, "thick_ortho",
                      {{120.0, 0.0002},  // measured 125.4 dB, 0.000002
                       {81.7, 0.0015},   // measured 84.8 dB, 0.00108
                       {31.3, 0.21}},    // measured 34.4-36.6 dB, 0.12-0.18 (47 levels)*
                      {81.7, 0.0015});   // measured 84.8 dB, 0.00108
}

// One cube (a hexahedron's tets) four unit distances deep at opacity 0.99, the scalar running
// across it from 0 to 1 so that the colour changes along and across every ray: the picture is
// the colour just behind the front face, which the old (front, back, length) table blurred.
TEST(Renderer, OneOpaqueCubeWithTheColourChangingInside) {
    UnstructuredMesh cube;
    cube.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                   {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
    cube.add_cell(CellType::kHexahedron, {0, 1, 2, 3, 4, 5, 6, 7});
    Fixture fx;
    fx.mesh = tetrahedralize(cube).value();
    fx.adjacency = build_face_adjacency(fx.mesh).value();
    for (const Vec3& p : fx.mesh.points()) {
        fx.scalar.push_back(static_cast<float>((p.x + p.y + 2 * p.z) / 4.0));
    }
    const TransferFunction tf =
        TransferFunction::create(
            {{0.0, {0.1, 0.1, 0.9}}, {0.5, {0.9, 0.9, 0.1}}, {1.0, {0.9, 0.1, 0.1}}},
            {{0.0, 0.99}, {1.0, 0.99}}, 0.25)
            .value();
    const CameraFrame persp(looking_at({2.5, -1.8, 2.2}, {0.5, 0.5, 0.5}, false, 1), 128, 128);
    const CameraFrame ortho(looking_at({0.5, 0.5, 4}, {0.5, 0.5, 0.5}, true, 0.7), 128, 128);
    // The old (front, back, length) table: 37.3 and 62.5 dB, 28 and 2 levels off.
    check_integrators(fx, tf, persp, "cube_persp",
                      {{115.0, 0.0002},  // measured 120.6 dB, 0.00001
                       {80.4, 0.0015},   // measured 83.5 dB, 0.00113
                       {23.3, 0.17}},    // measured 26.3 dB, 0.145 (37 levels)
                      {80.4, 0.0015});   // measured 83.5 dB, 0.00113
    check_integrators(fx, tf, ortho, "cube_ortho",
                      {{110.0, 0.0002},  // measured 115.6 dB, 0.00002
                       {76.8, 0.0015},   // measured 79.9 dB, 0.00087
                       {18.5, 0.38}},    // measured 21.6 dB, 0.356 (91 levels)
                      {76.8, 0.0015});   // measured 79.9 dB, 0.00087
}

TEST(Renderer, CameraInsideTheMesh) {
    const Fixture fx = make_fixture(4, wavy, 5);
    const TransferFunction tf = wavy_tf();
    Camera c = looking_at({1.3, 1.7, 2.2}, {4, 3, 2.5}, false, 1);
    c.view_angle = 80;
    const CameraFrame frame(c, 96, 96);
    const Image reference = render_reference(fx.mesh, fx.scalar, tf, frame, Vec3(0.0));
    for (Integrator integrator : {Integrator::kExact, Integrator::kPreintegrated}) {
        const Image image = render(fx, tf, frame, integrator, Vec3(0.0));
        // Measured 88.6 dB, 0.00012 (exact); 89.5 dB, 0.00030 (preintegrated).
        const ImageBounds bounds = integrator == Integrator::kExact ? ImageBounds{85.5, 0.0006}
                                                                    : ImageBounds{86.5, 0.0012};
        EXPECT_TRUE(images_match(image, reference, Vec3f(0.0f), bounds,
                                 "inside_" + std::string(integrator_name(integrator))));
    }
}

TEST(Renderer, BitIdenticalWhateverTheThreadCount) {
#if !TETRENDER_HAS_TBB
    GTEST_SKIP() << "serial build (TETRENDER_WITH_TBB=OFF): one thread only, nothing to compare";
#endif
    const Fixture fx = make_fixture(4, wavy, 7);
    const TransferFunction tf = wavy_tf();
    const CameraFrame frame(looking_at({8, -5, 6}, {2, 2, 2}, false, 1), 150, 110);
    for (Integrator integrator :
         {Integrator::kExact, Integrator::kPreintegrated, Integrator::kExpTexture}) {
        SCOPED_TRACE(std::string(integrator_name(integrator)));
        std::vector<float> alpha_one, alpha_two, alpha_seven;
        set_thread_count(1);
        const Image one = render(fx, tf, frame, integrator, Vec3(0.1), nullptr, &alpha_one);
        set_thread_count(2);
        const Image two = render(fx, tf, frame, integrator, Vec3(0.1), nullptr, &alpha_two);
        set_thread_count(7);
        const Image seven = render(fx, tf, frame, integrator, Vec3(0.1), nullptr, &alpha_seven);
        set_thread_count(0);
        // The alpha asked for as well (not all zero, which would be identical trivially).
        EXPECT_GT(*std::max_element(alpha_one.begin(), alpha_one.end()), 0.5f);
        EXPECT_TRUE(testing::bit_identical(alpha_one, alpha_two));
        EXPECT_TRUE(testing::bit_identical(alpha_one, alpha_seven));
        ASSERT_EQ(one.pixels.size(), two.pixels.size());
        // Not a blank picture (which would be identical trivially).
        EXPECT_LT(psnr(one, Image(one.width, one.height, Vec3f(0.1f))), 30.0);
        EXPECT_EQ(
            std::memcmp(one.pixels.data(), two.pixels.data(), one.pixels.size() * sizeof(Vec3f)),
            0);
        EXPECT_EQ(
            std::memcmp(one.pixels.data(), seven.pixels.data(), one.pixels.size() * sizeof(Vec3f)),
            0);
    }
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
        RenderInputs in = inputs(fx, shader, frame, order);
        in.opaque_color = &layer.color;
        in.opaque_depth = &layer.depth;
        const Image image = render_projected_tetrahedra(in);
        const Vec3 normal = glm::normalize(Vec3(-0.3, 0, 1));
        double worst = 0.0;
        int checked = 0;
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
                    worst = std::max(worst, std::abs(image.at(i, j)[k] - expected[k]));
                }
                ++checked;
            }
        }
        std::printf(
            "[ opaque_plane_%s ] largest difference from the closed form %.2g over %d "
            "pixels\n",
            parallel ? "ortho" : "persp", worst, checked);
        EXPECT_GT(checked, 500);  // 1936 orthographic, 622 in perspective
        EXPECT_LT(worst, 2e-6);   // measured 2.1e-7 and 1.6e-7 (single precision)
    }
}

// A box [0, 4]^3 whose scalar runs with x from 0 to 1 and whose opacity ramps from none to
// 0.9 per half unit: rays near x = 0 are nearly transparent, rays near x = 4 opaque, and the
// pictures' margins hold no volume.
float ramp_in_x(const Vec3& p) { return static_cast<float>(p.x / 4.0); }

TransferFunction ramp_tf() {
    return TransferFunction::create({{0.0, {0.1, 0.2, 0.9}}, {1.0, {0.9, 0.3, 0.1}}},
                                    {{0.0, 0.0}, {0.5, 0.05}, {1.0, 0.9}}, 0.5)
        .value();
}

// The cameras the alpha tests look with: nearly down z, so that the ray through (3.5, 2, 2)
// crosses the whole box where it is opaque (x in [3.1, 3.9]: optical depth above 6).
const Camera kAlphaCameras[] = {
    looking_at({4.5, 3.5, 16}, {2, 2, 2}, true, 3.2),  // orthographic
    [] {
        Camera c = looking_at({5, 0.5, 14}, {2, 2, 2}, false, 1);
        c.view_angle = 30;
        return c;
    }(),  // perspective
};

// One view of the alpha tests: an integrator's shader and a camera's frame, the box's visibility
// order in it, and the opaque layer of a tilted plane through the box (z = 1 + 0.3 x).
struct AlphaView {
    const Fixture& fx;
    std::string name;
    SegmentShader shader;
    CameraFrame frame;
    std::vector<CellId> order;
    SurfaceMesh plane = testing::tilted_plane(-1, 5, 0.7, 2.5);
    OpaqueLayer layer = testing::plane_layer(plane, frame);

    AlphaView(const Fixture& f, const TransferFunction& tf, Integrator integrator,
              const Camera& camera)
        : fx(f),
          name(std::string(integrator_name(integrator)) +
               (camera.parallel ? " orthographic" : " perspective")),
          shader(tf, integrator, longest_edge(f.mesh)),
          frame(camera, 64, 64) {
        VisibilitySorter sorter;
        sorter.sort(fx.mesh, fx.adjacency, SortView::from_camera(frame), SortMethod::kMpvo, order);
    }

    // The render callable of the alpha checks (tests/project/alpha_check.h): the picture over
    // `background`, or over the layer (its depth, and its colour too when `color`).
    Image operator()(const Vec3& background, bool depth, bool color,
                     std::vector<float>* alpha) const {
        RenderInputs in = inputs(fx, shader, frame, order);
        in.background = background;
        if (depth) {
            in.opaque_depth = &layer.depth;
            if (color) in.opaque_color = &layer.color;
        }
        return render_projected_tetrahedra(in, nullptr, alpha);
    }
};

// Calls `f` with each view of the alpha tests: the ramp box, each integrator, each camera; stops
// at a fatal failure, as an ASSERT in the loop's body would.
template <class F>
void for_each_alpha_view(F&& f) {
    const Fixture fx = make_fixture(4, ramp_in_x, 5);
    const TransferFunction tf = ramp_tf();
    for (Integrator integrator :
         {Integrator::kPreintegrated, Integrator::kExact, Integrator::kExpTexture}) {
        for (const Camera& camera : kAlphaCameras) {
            const AlphaView view(fx, tf, integrator, camera);
            SCOPED_TRACE(view.name);
            f(view);
            if (::testing::Test::HasFatalFailure()) return;
        }
    }
}

// For each integrator and camera: the picture over a non-black background, and over an opaque
// layer's colour (a tilted plane through the box), is the picture over black (with the layer's
// depth, no colour: how a rank renders its part) plus (1 - alpha) times what is behind. Alpha
// lies in [0, 1], is exactly 0 where the rays miss the box, above 0.99 where the box is opaque,
// and the opaque layer lowers it.
TEST(Renderer, AlphaComposesThePictureOverAnyBackgroundFromTheOneOverBlack) {
    double worst = 0;
    for_each_alpha_view([&](const AlphaView& view) {
        ASSERT_GT(view.layer.pixels_covered, 1000u);
        testing::AlphaRun r;
        // Measured at most 3.7e-7 over integrators and cameras (float rounding: colour and
        // alpha composited in float, one over per fragment); bound 1e-6.
        ASSERT_NO_FATAL_FAILURE(testing::expect_alpha_composes(
            "alpha " + view.name, view, Vec3(0.3, 0.6, 0.9), view.layer.color, 1e-6, &r));
        worst = std::max(worst, r.largest_difference());
        const testing::AlphaCounts n =
            testing::count_missed_and_lowered(view.frame, r, 4.0, 1e-3, 1e-6f);
        // Measured 1991 to 2094 pixels missed, 530 to 883 lowered (the plane cuts segments).
        EXPECT_GT(n.missed, 1500u);
        EXPECT_GT(n.lowered, 400u);
        // The ray through (3.5, 2, 2) crosses the box where it is opaque.
        EXPECT_GT(r.alpha[testing::pixel_of(view.frame, Vec3(3.5, 2.0, 2.0))], 0.99f);
    });
    std::printf("[ alpha ] largest difference over all: %.2g\n", worst);
}

TEST(Renderer, AskingForAlphaChangesNoBitOfThePicture) {
    for_each_alpha_view([](const AlphaView& view) {
        testing::expect_alpha_changes_no_bit(view, Vec3(0.3, 0.6, 0.9));
    });
}

// Whether `image` (over black) matches the reference ray caster's picture of the fixture.
::testing::AssertionResult matches_reference(const Image& image, const Fixture& fx,
                                             const TransferFunction& tf, const CameraFrame& frame,
                                             const ImageBounds& bounds, const std::string& name) {
    const Image reference = render_reference(fx.mesh, fx.scalar, tf, frame, Vec3(0.0));
    return images_match(image, reference, Vec3f(0.0f), bounds, name);
}

// Cells whose scalar range the transfer function leaves clear are not drawn (cells_drawn counts
// the others), and the picture still matches the reference ray caster, which integrates every
// cell: here the opacity is zero below the wavy field's middle value.
TEST(Renderer, CellsTheTransferFunctionLeavesClearAreNotDrawn) {
    const Fixture fx = make_fixture(4, wavy, 3);
    const TransferFunction tf =
        TransferFunction::create({{0.0, {0.1, 0.2, 0.9}}, {1.0, {0.9, 0.1, 0.1}}},
                                 {{0.0, 0.0}, {0.5, 0.0}, {1.0, 0.8}}, 1.5)
            .value();
    const CameraFrame frame(looking_at({9, -6, 7}, {2, 2, 2}, false, 1), 256, 256);
    std::size_t clear = 0;
    for (CellId t = 0; t < fx.mesh.num_tets(); ++t) {
        float hi = -1;
        for (PointId p : fx.mesh.tet(t)) hi = std::max(hi, fx.scalar[p]);
        clear += hi <= 0.5f;
    }
    ASSERT_GT(clear, fx.mesh.num_tets() / 5);  // measured 192 of 534
    ASSERT_LT(clear, fx.mesh.num_tets() * 4 / 5);
    RenderStats stats;
    const Image image = render(fx, tf, frame, Integrator::kExact, Vec3(0.0), &stats);
    EXPECT_EQ(stats.cells_drawn, fx.mesh.num_tets() - clear);  // the whole mesh is in view
    EXPECT_TRUE(matches_reference(image, fx, tf, frame,
                                  {90.4, 0.0005},  // measured 93.5 dB, 0.00014
                                  "clear_cells_exact"));
}

// Cells are composited front to back, and a pixel whose transmittance is spent (below 2^-24)
// takes no more fragments: an opaque transfer function draws far fewer fragments than a thin
// one over the same cells, and its picture still matches the reference ray caster.
TEST(Renderer, SpentPixelsTakeNoMoreFragments) {
    const Fixture fx = make_fixture(4, wavy, 3);
    const CameraFrame frame(looking_at({9, -6, 7}, {2, 2, 2}, false, 1), 96, 96);
    const std::vector<ColorPoint> colors = {{0.0, {0.1, 0.2, 0.9}}, {1.0, {0.9, 0.1, 0.1}}};
    const TransferFunction thin = TransferFunction::create(colors, {{0.0, 0.05}}, 1.0).value();
    const TransferFunction opaque = TransferFunction::create(colors, {{0.0, 0.999}}, 0.05).value();
    RenderStats thin_stats, opaque_stats;
    render(fx, thin, frame, Integrator::kPreintegrated, Vec3(0.0), &thin_stats);
    const Image image =
        render(fx, opaque, frame, Integrator::kPreintegrated, Vec3(0.0), &opaque_stats);
    EXPECT_EQ(thin_stats.cells_drawn, opaque_stats.cells_drawn);
    std::printf("fragments: %zu opaque, %zu thin\n", opaque_stats.fragments, thin_stats.fragments);
    EXPECT_LT(opaque_stats.fragments, thin_stats.fragments / 3);  // measured 5016 of 37635
    EXPECT_TRUE(matches_reference(image, fx, opaque, frame,
                                  {96.0, 0.0004},  // measured 99.0 dB, 0.00006
                                  "spent_pixels_preintegrated"));
}

// The fragments under perspective (four pixels of a row at once, denominators stepped along
// the row) are those of the per-pixel ray test, CellFragments::segment: the same pixels, the
// same ray parameters and scalars up to rounding. A pixel whose ray grazes the cell (a segment
// of length near rounding) may fall either way.
TEST(Renderer, SteppedFragmentsAreThoseOfThePerPixelRayTest) {
    const Fixture fx = make_fixture(3, wavy, 5);
    const CameraFrame frame(looking_at({6, -4, 5}, {1.5, 1.5, 1.5}, false, 1), 97, 83);
    std::vector<CellId> cells(fx.mesh.num_tets());
    for (CellId t = 0; t < cells.size(); ++t) cells[t] = t;
    const TileBins bins = bin_cells(fx.mesh, cells, frame);
    std::size_t fragments = 0, tested = 0, differing = 0;
    double worst_t = 0, worst_s = 0, longest_differing = 0;
    for (std::size_t tile = 0; tile < bins.num_tiles(); ++tile) {
        TileRays rays;
        tile_rays(bins, tile, frame, rays);
        for (std::uint32_t index : bins.bins[tile]) {
            const CellFragments cell(fx.mesh, fx.scalar, cells[index], frame);
            const ScreenBox& box = bins.boxes[index];
            // Per tile pixel: the per-pixel test's fragment (t_in, t_out, s_in, s_out), if any.
            std::vector<std::array<double, 4>> expected(kFragmentTile * kFragmentTile);
            std::vector<char> has(kFragmentTile * kFragmentTile, 0);
            for (int y = std::max(box.y0, rays.y0); y <= std::min(box.y1, rays.y1); ++y) {
                for (int x = std::max(box.x0, rays.x0); x <= std::min(box.x1, rays.x1); ++x) {
                    const int local = (y - rays.y0) * kFragmentTile + (x - rays.x0);
                    auto& e = expected[local];
                    has[local] =
                        cell.segment(rays.at(x, y), std::numeric_limits<double>::infinity(), e[0],
                                     e[1], e[2], e[3]);
                    ++tested;
                }
            }
            for_each_fragment(
                cell, box, rays, frame.width(), {},
                [&](int x, int y, double t_in, double t_out, double s_in, double s_out) {
                    const int local = (y - rays.y0) * kFragmentTile + (x - rays.x0);
                    ++fragments;
                    if (!has[local]) {  // found here only
                        ++differing;
                        longest_differing = std::max(longest_differing, t_out - t_in);
                        return;
                    }
                    has[local] = 2;
                    const auto& e = expected[local];
                    worst_t = std::max({worst_t, std::abs(t_in - e[0]), std::abs(t_out - e[1])});
                    worst_s = std::max({worst_s, std::abs(s_in - e[2]), std::abs(s_out - e[3])});
                });
            for (int local = 0; local < kFragmentTile * kFragmentTile; ++local) {
                if (has[local] != 1) continue;  // found by the per-pixel test only
                ++differing;
                longest_differing =
                    std::max(longest_differing, expected[local][1] - expected[local][0]);
            }
        }
    }
    std::printf(
        "stepped fragments: %zu of %zu pixels tested, %zu differing (longest %.3g); "
        "largest differences t %.3g, s %.3g\n",
        fragments, tested, differing, longest_differing, worst_t, worst_s);
    EXPECT_GT(fragments, tested / 4);  // measured 25210 of 56638
    EXPECT_LE(differing, 4u);          // measured 1
    EXPECT_LT(longest_differing, 1e-9);
    EXPECT_LT(worst_t, 1e-12);  // measured 1.8e-14 (t is about 7)
    EXPECT_LT(worst_s, 1e-12);  // measured 6.7e-15
}

// Preconditions whose violation would read or write out of bounds abort with the check that
// failed (TR_CHECK, core/check.h): a bug in the caller, not bad input.
TEST(RendererDeathTest, PreconditionsAreChecked) {
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    const Fixture fx = make_fixture(2, wavy, 1);
    const TransferFunction tf = wavy_tf();
    const CameraFrame frame(looking_at({6, -4, 5}, {1, 1, 1}, false, 1), 32, 24);
    const SegmentShader shader(tf, Integrator::kExact, longest_edge(fx.mesh));
    std::vector<CellId> order(fx.mesh.num_real_tets());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<CellId>(i);
    const RenderInputs in = inputs(fx, shader, frame, order);
    // A scalar short of one per point.
    const std::vector<float> short_scalar(fx.scalar.begin(), fx.scalar.end() - 1);
    RenderInputs bad = in;
    bad.scalar = short_scalar;
    EXPECT_DEATH(render_projected_tetrahedra(bad),
                 "internal check failed: TR_CHECK_EQ\\(in\\.scalar\\.size\\(\\), "
                 "mesh\\.num_points\\(\\)\\) with [0-9]+ != [0-9]+");
    // An order id past the last real tet.
    std::vector<CellId> bad_order = order;
    bad_order.back() = static_cast<CellId>(fx.mesh.num_real_tets());
    bad = in;
    bad.order = bad_order;
    EXPECT_DEATH(render_projected_tetrahedra(bad),
                 "internal check failed: TR_CHECK\\(t < num_real\\)");
    // Opaque buffers of another size than the image.
    const Image small_color(16, 24);
    bad = in;
    bad.opaque_color = &small_color;
    EXPECT_DEATH(render_projected_tetrahedra(bad),
                 "TR_CHECK_EQ\\(in\\.opaque_color->width, w\\) with 16 != 32");
    const std::vector<double> small_depth(32 * 23, 1.0);
    bad = in;
    bad.opaque_depth = &small_depth;
    EXPECT_DEATH(render_projected_tetrahedra(bad), "TR_CHECK_EQ\\(in\\.opaque_depth->size\\(\\)");
    // No shader.
    bad = in;
    bad.shader = nullptr;
    EXPECT_DEATH(render_projected_tetrahedra(bad), "internal check failed: TR_CHECK");
    // The correct call renders.
    EXPECT_EQ(render_projected_tetrahedra(in).pixels.size(), std::size_t{32} * 24);
}

}  // namespace
}  // namespace tr
