// The scene methods texture-advection and spot-noise (pipeline/methods/texture_advection_method.h):
// their pictures against the flowtex libraries' own frames (a scene whose volume is clear),
// depth order against opaque geometry and between sheets, attenuation by the volume in front.
#include <flowtex/advect_frames.h>
#include <flowtex/advected_sheets.h>
#include <flowtex/sheet_raster.h>
#include <flowtex/spot_noise_frames.h>
#include <mesh/field.h>
#include <pipeline/flow_volume_scene.h>
#include <pipeline/pipeline.h>
#include <project/opaque_geometry.h>
#include <tests/flowtex/fixtures.h>
#include <tests/flowtex/scene_fixtures.h>

#include <gtest/gtest.h>

#include <cmath>

namespace tr {
namespace {

using testing::advection_method;
using testing::flow_mesh;
using testing::flow_scene;
using testing::kSize;
using testing::top_camera;

std::vector<Image> scene_frames(const Scene& scene, NamedStats* stats = nullptr) {
    Pipeline pipeline;
    RenderOptions options;
    std::vector<Image> frames;
    options.on_frame = [&](int k, const Image& image) -> Status {
        EXPECT_EQ(k, static_cast<int>(frames.size()));
        frames.push_back(image);
        return {};
    };
    auto result = pipeline.render(scene, options);
    EXPECT_TRUE(result.ok()) << (result.ok() ? "" : result.error().to_string());
    if (result.ok() && stats) *stats = result->stats;
    return frames;
}

// Frame for frame, bit for bit.
void expect_same_frames(const std::vector<Image>& frames, const std::vector<Image>& expected) {
    ASSERT_EQ(frames.size(), expected.size());
    for (std::size_t k = 0; k < frames.size(); ++k) {
        SCOPED_TRACE(k);
        EXPECT_TRUE(frames[k].pixels == expected[k].pixels);
    }
}

// The method spot-noise over the fixture's "velocity" (no contour given).
MethodSpec spot_noise_method(std::int64_t count, std::int64_t steps) {
    MethodSpec m;
    m.name = "spot-noise";
    m.options["vectors"] = std::string("velocity");
    m.options["count"] = count;
    m.options["steps"] = steps;
    return m;
}

Image render(const Scene& scene) {
    Pipeline pipeline;
    auto result = pipeline.render(scene);
    EXPECT_TRUE(result.ok()) << (result.ok() ? "" : result.error().to_string());
    return result.ok() ? result->image : Image();
}

// In a clear volume, an opaque sheet's frames are advect_frames' frames, bit for bit.
TEST(FlowtexScene, ClearVolumeSheetEqualsAdvectFrames) {
    const auto mesh = flow_mesh();
    const FaceAdjacency adjacency = build_face_adjacency(*mesh).value();
    const VelocityField velocity =
        VelocityField::steady(*mesh, *find_field(mesh->point_fields(), "velocity")).value();
    AdvectFramesOptions o;
    o.slice_point = Vec3(0, 0, 0.1);
    o.slice_normal = Vec3(0, 0, 1);
    o.sheet_resolution = 64;
    o.steps = 6;
    o.dt = 0.02;
    o.width = o.height = kSize;
    std::vector<Image> expected;
    ASSERT_TRUE(advect_frames(*mesh, adjacency, velocity, o, [&](int, const Image& image) {
                    expected.push_back(image);
                    return Status{};
                }).ok());
    // The subcommand's camera: head-on to its sheet.
    AdvectedSheetsOptions so;
    so.slices = {{Vec3(0, 0, 0.1), Vec3(0, 0, 1)}};
    so.sheet_resolution = 64;
    so.dt = 0.02;
    const auto sheets = AdvectedSheets::create(*mesh, adjacency, velocity, so).value();
    Scene scene = flow_scene(0.0);
    scene.camera = sheet_camera(sheets->sheet(0), kSize, kSize);
    scene.method = advection_method({{0, 0, 0.1, 0, 0, 1}}, 6, 1.0);
    NamedStats stats;
    const std::vector<Image> frames = scene_frames(scene, &stats);
    EXPECT_EQ(stats.number("layers"), 1);
    EXPECT_EQ(stats.number("volume_renders"), 3);
    expect_same_frames(frames, expected);
    EXPECT_FALSE(frames[0].pixels == frames[6].pixels);  // the texture moved
    // A single render is the last frame.
    EXPECT_TRUE(render(scene).pixels == expected.back().pixels);
}

// An opaque disk between the eye and the sheet hides it: those pixels are the volume over the
// disk alone (the scene without the method), exactly; a disk behind the sheet is hidden by it.
TEST(FlowtexScene, OpaqueGeometryInFrontHidesTheSheet) {
    Scene scene = flow_scene(0.3, 1.0);
    scene.camera = top_camera(true);
    auto front = std::make_shared<const SurfaceMesh>(make_cylinder_surface(0.8, 0.5, 1.0, 32));
    auto back = std::make_shared<const SurfaceMesh>(make_cylinder_surface(0.8, -1.0, -0.5, 32));
    scene.opaque.push_back({{}, {}, false, 0, front, Vec3(0.9, 0.2, 0.2)});
    const Image volume_only = render(scene);
    scene.method = advection_method({{0, 0, 0, 0, 0, 1}}, 2, 0.8);
    const Image with_sheet = render(scene);
    const CameraFrame frame(scene.camera, kSize, kSize);
    const OpaqueLayer disk = render_opaque({{front.get(), Vec3(1.0)}}, frame, Vec3(0.0));
    std::size_t hidden = 0, shown = 0;
    for (std::size_t p = 0; p < with_sheet.pixels.size(); ++p) {
        if (std::isfinite(disk.depth[p])) {
            ++hidden;
            EXPECT_EQ(with_sheet.pixels[p], volume_only.pixels[p]) << p;
        } else if (with_sheet.pixels[p] != volume_only.pixels[p]) {
            ++shown;
        }
    }
    EXPECT_GT(hidden, 900u);  // measured 944 of 9,216 pixels
    EXPECT_GT(shown, 6000u);  // the sheet beside the disk; measured 6,800
    // Behind the sheet the disk is no longer hidden by it ... but covered: the pictures with
    // and without the back disk differ only where the sheet lets it through (opacity 0.8).
    scene.opaque = {{{}, {}, false, 0, back, Vec3(0.9, 0.2, 0.2)}};
    const Image over_back = render(scene);
    scene.method.reset();
    const Image back_only = render(scene);
    std::size_t differ = 0;
    for (std::size_t p = 0; p < over_back.pixels.size(); ++p) {
        differ += over_back.pixels[p] != back_only.pixels[p];
    }
    EXPECT_GT(differ, 7000u);  // measured 7,744
}

// The colour each sheet alone gives at frame `steps` (opaque, clear volume, black background).
std::vector<Vec3f> sheet_colours(const Camera& camera, const std::vector<double>& slice,
                                 int steps) {
    Scene scene = flow_scene(0.0);
    scene.camera = camera;
    scene.method = advection_method({slice}, steps, 1.0);
    return render(scene).pixels;
}

// Two sheets at z = -0.5 and z = 0.5 of opacity 0.6: where both are drawn the picture is
// 0.6 near + 0.4 x 0.6 far + 0.16 background, and turning the camera round swaps near and far.
TEST(FlowtexScene, TwoSheetsCompositeInDepthOrder) {
    // Tilted apart so that their textures differ (the flow does not depend on z); the low one
    // stays below z = 0.1 over the mesh.
    const std::vector<double> low{0, 0, -0.5, 0.3, 0, 1}, high{0, 0, 0.5, 0, 0, 1};
    for (bool from_above : {true, false}) {
        SCOPED_TRACE(from_above);
        const Camera camera = top_camera(from_above);
        const std::vector<Vec3f> c_low = sheet_colours(camera, low, 3);
        const std::vector<Vec3f> c_high = sheet_colours(camera, high, 3);
        Scene scene = flow_scene(0.0);
        scene.camera = camera;
        scene.method = advection_method({low, high}, 3, 0.6);
        NamedStats stats;
        const std::vector<Image> frames = scene_frames(scene, &stats);
        ASSERT_EQ(frames.size(), 4u);
        EXPECT_EQ(stats.number("layers"), 2);
        const std::vector<Vec3f>& near = from_above ? c_high : c_low;
        const std::vector<Vec3f>& far = from_above ? c_low : c_high;
        double worst = 0, worst_swapped = 0;
        std::size_t both = 0;
        for (std::size_t p = 0; p < near.size(); ++p) {
            if (near[p] == Vec3f(0.0f) || far[p] == Vec3f(0.0f)) continue;  // not on both
            ++both;
            const Vec3f expected = 0.6f * near[p] + 0.4f * 0.6f * far[p];
            const Vec3f swapped = 0.6f * far[p] + 0.4f * 0.6f * near[p];
            worst = std::max(worst, double(glm::length(frames[3].pixels[p] - expected)));
            worst_swapped =
                std::max(worst_swapped, double(glm::length(frames[3].pixels[p] - swapped)));
        }
        EXPECT_GT(both, 7000u);         // measured 7,395 of 9,216
        EXPECT_LT(worst, 1e-6);         // measured: float rounding
        EXPECT_GT(worst_swapped, 0.1);  // the order matters: the other order is far off
    }
}

// A uniform medium between the eye and an opaque sheet at z = 0 (depth d = 2 of it in front):
// black, it leaves the sheet's colour times exp(-kappa d); glowing white, it adds
// 1 - exp(-kappa d) (the emission-absorption integral of a constant medium, closed form).
TEST(FlowtexScene, VolumeInFrontAttenuatesTheSheet) {
    const double a = 0.3;  // opacity per unit length
    const double kappa = -std::log(1.0 - a);
    const double through = std::exp(-kappa * 2.0);
    const Camera camera = top_camera(true);
    const std::vector<Vec3f> clear = sheet_colours(camera, {0, 0, 0, 0, 0, 1}, 2);
    for (double glow : {0.0, 1.0}) {
        SCOPED_TRACE(glow);
        Scene scene = flow_scene(a, glow);
        scene.camera = camera;
        scene.method = advection_method({{0, 0, 0, 0, 0, 1}}, 2, 1.0);
        const Image seen = render(scene);
        double worst = 0;
        std::size_t counted = 0;
        for (std::size_t p = 0; p < clear.size(); ++p) {
            if (!(clear[p].x > 0.05f)) continue;
            ++counted;
            const double expected = glow * (1.0 - through) + through * clear[p].x;
            worst = std::max(worst, std::abs(seen.pixels[p].x - expected));
        }
        EXPECT_GT(counted, 7000u);  // measured 7,744
        EXPECT_LT(worst, 1e-6);     // measured 2.4e-7 (black), 2.9e-7 (white): float rounding
    }
}

// A medium that varies along the view (s = z, colour and opacity ramps in s) in front of an
// opaque sheet at z = 0, seen from above: each pixel against the ray integral from z = 2 down to
// the sheet by the midpoint rule in 20,000 steps (independent of the renderer's pre-integrated
// table), plus the sheet's colour attenuated by the medium's transmittance.
TEST(FlowtexScene, VaryingVolumeInFrontMatchesTheRayIntegral) {
    const Camera camera = top_camera(true);
    const std::vector<Vec3f> clear = sheet_colours(camera, {0, 0, 0, 0, 0, 1}, 2);
    Scene scene = flow_scene(0.0);
    const TransferFunction tf =
        TransferFunction::create(
            {{-2, Vec3(0.1, 0.2, 0.9)}, {0, Vec3(0.9, 0.6, 0.1)}, {2, Vec3(1.0, 1.0, 1.0)}},
            {{-2, 0.0}, {0.5, 0.1}, {2, 0.6}}, 1.0)
            .value();
    scene.volumes[0].transfer_function = tf;
    scene.camera = camera;
    scene.method = advection_method({{0, 0, 0, 0, 0, 1}}, 2, 1.0);
    const Image seen = render(scene);
    // The ray from z = 2 to 0 (s = z): light L and transmittance T.
    const int n = 20000;
    const double h = 2.0 / n;
    Vec3 light(0.0);
    double optical = 0;
    for (int i = 0; i < n; ++i) {
        const double z = 2.0 - (i + 0.5) * h;
        const double kappa = tf.extinction(z);
        light += std::exp(-optical - 0.5 * kappa * h) * tf.color(z) * kappa * h;
        optical += kappa * h;
    }
    const double through = std::exp(-optical);
    double worst = 0;
    std::size_t counted = 0;
    for (std::size_t p = 0; p < clear.size(); ++p) {
        if (!(clear[p].x > 0.05f)) continue;
        ++counted;
        const Vec3 expected = light + through * Vec3(clear[p]);
        worst = std::max(worst, glm::length(Vec3(seen.pixels[p]) - expected));
    }
    EXPECT_GT(counted, 7000u);  // measured 7,744
    // Measured 5.8e-5 (the pre-integrated table's accuracy against the fine midpoint sum; light
    // 0.506, 0.465, 0.398, transmittance 0.481); bound 1e-4, the measured value plus about 70%.
    EXPECT_LT(worst, 1e-4);
}

// Spot noise in a clear volume: the frames of spot_noise_frames from the same camera, bit for bit.
TEST(FlowtexScene, ClearVolumeSpotsEqualSpotNoiseFrames) {
    const auto mesh = flow_mesh();
    const FaceAdjacency adjacency = build_face_adjacency(*mesh).value();
    const VelocityField velocity =
        VelocityField::steady(*mesh, *find_field(mesh->point_fields(), "velocity")).value();
    Camera camera;
    camera.position = Vec3(5, -6, 4);
    camera.focal_point = Vec3(0.0);
    camera.view_up = Vec3(0, 0, 1);
    SpotNoiseFramesOptions o;
    o.scalar = "s";
    o.spots.iso = 0.25;
    o.spots.count = 3000;
    o.spots.dt = 0;  // the time step of `tetrender spotnoise` (and of the scene): chosen
    o.steps = 4;
    o.width = o.height = kSize;
    o.camera = camera;
    std::vector<Image> expected;
    ASSERT_TRUE(spot_noise_frames(*mesh, adjacency, velocity, o, [&](int, const Image& image) {
                    expected.push_back(image);
                    return Status{};
                }).ok());
    Scene scene = flow_scene(0.0);
    scene.camera = camera;
    MethodSpec m = spot_noise_method(3000, 4);
    m.options["iso"] = 0.25;
    scene.method = m;
    const std::vector<Image> frames = scene_frames(scene);
    expect_same_frames(frames, expected);
    EXPECT_FALSE(frames[0].pixels == frames[4].pixels);
    // The method's seed places the spots: another seed, other spots.
    scene.method->seed = 7;
    EXPECT_FALSE(render(scene).pixels == frames[4].pixels);
}

// A planar 2D mesh of quads over [-2, 2]^2 at z = 0 with the 2-component velocity
// (0.3 - y, x) and a scalar "s" = 0, handed to a scene: a 2D flow.
Scene flow_2d_scene() {
    auto mesh = std::make_shared<UnstructuredMesh>();
    const int n = 16;
    std::vector<double> v, s;
    for (int j = 0; j <= n; ++j) {
        for (int i = 0; i <= n; ++i) {
            const double x = -2.0 + 4.0 * i / n, y = -2.0 + 4.0 * j / n;
            mesh->points.push_back(Vec3(x, y, 0.0));
            v.insert(v.end(), {0.3 - y, x});
            s.push_back(0.0);
        }
    }
    for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i) {
            const std::int64_t a = j * (n + 1) + i;
            mesh->add_cell(CellType::kQuad, {a, a + 1, a + n + 2, a + n + 1});
        }
    }
    mesh->point_fields.push_back(make_double_field("velocity", 2, v));
    mesh->point_fields.push_back(make_double_field("s", 1, s));
    Scene scene = flow_scene(0.0);
    scene.volumes[0].tets = nullptr;
    scene.volumes[0].data = mesh;
    scene.volumes[0].mesh = "flow_2d";
    scene.camera = top_camera(true);
    return scene;
}

// On a 2D mesh the sheet is the mesh's plane and no volume is drawn: an opaque sheet's frames
// are advect_frames' frames over the same slab, bit for bit, with no volume render.
TEST(FlowtexScene, A2DMeshsSheetEqualsAdvectFramesWithNoVolume) {
    Scene scene = flow_2d_scene();
    Pipeline pipeline;
    const FlowDomain domain = pipeline.flow_domain(scene.volumes[0]).value();
    ASSERT_TRUE(domain.planar.has_value());
    const VelocityField velocity = load_velocity(domain, "velocity", false).value();
    AdvectFramesOptions o;
    o.slice_point = domain.planar->point;
    o.slice_normal = domain.planar->normal;
    o.sheet_resolution = 64;
    o.steps = 6;
    o.dt = 0.02;
    o.width = o.height = kSize;
    o.view_up = upright_view_up(domain.planar->normal);
    std::vector<Image> expected;
    ASSERT_TRUE(
        advect_frames(domain.mesh(), *domain.adjacency, velocity, o, [&](int, const Image& image) {
            expected.push_back(image);
            return Status{};
        }).ok());
    AdvectedSheetsOptions so;
    so.slices = {{domain.planar->point, domain.planar->normal}};
    so.sheet_resolution = 64;
    so.dt = 0.02;
    const auto sheets =
        AdvectedSheets::create(domain.mesh(), *domain.adjacency, velocity, so).value();
    scene.camera = sheet_camera(sheets->sheet(0), kSize, kSize, o.view_up);
    MethodSpec m = advection_method({}, 6, 1.0);
    m.options.erase("slices");  // the default: the 2D mesh's plane
    scene.method = m;
    NamedStats stats;
    const std::vector<Image> frames = scene_frames(scene, &stats);
    EXPECT_EQ(stats.number("volume_renders"), 0);
    expect_same_frames(frames, expected);
    EXPECT_FALSE(frames[0].pixels == frames[6].pixels);  // the texture moved
}

// Spot noise on a 2D mesh needs no contour: the scene's frames are spot_noise_frames' on the
// slab (spots over the whole sheet), bit for bit; on a 3D mesh `iso` stays required.
TEST(FlowtexScene, A2DMeshsSpotsEqualSpotNoiseFramesWithNoContour) {
    Scene scene = flow_2d_scene();
    Pipeline pipeline;
    const FlowDomain domain = pipeline.flow_domain(scene.volumes[0]).value();
    const VelocityField velocity = load_velocity(domain, "velocity", false).value();
    SpotNoiseFramesOptions o;
    o.planar = domain.planar;
    o.spots.count = 2000;
    o.spots.dt = 0;
    o.steps = 4;
    o.width = o.height = kSize;
    o.camera = scene.camera;
    std::vector<Image> expected;
    ASSERT_TRUE(spot_noise_frames(domain.mesh(), *domain.adjacency, velocity, o,
                                  [&](int, const Image& image) {
                                      expected.push_back(image);
                                      return Status{};
                                  })
                    .ok());
    const MethodSpec m = spot_noise_method(2000, 4);
    scene.method = m;
    const std::vector<Image> frames = scene_frames(scene);
    expect_same_frames(frames, expected);
    EXPECT_FALSE(frames[0].pixels == frames[4].pixels);
    Scene three_d = flow_scene(0.0);
    three_d.camera = scene.camera;
    three_d.method = m;
    const auto refused = Pipeline().render(three_d);
    ASSERT_FALSE(refused.ok());
    EXPECT_NE(refused.error().to_string().find("iso"), std::string::npos)
        << refused.error().to_string();
}

}  // namespace
}  // namespace tr
