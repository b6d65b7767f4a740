// Annotations on a rendered scene: the legend beside the volume (not over it), the bounding
// box on the meshes' projected corners, nothing drawn when nothing is asked.
#include <mesh/tetrahedralize.h>
#include <pipeline/annotations.h>
#include <pipeline/quick_scene.h>
#include <project/colormap.h>
#include <tests/support/mixed_grid.h>

#include <gtest/gtest.h>

#include <cmath>

namespace tr {
namespace {

Scene grid_scene() {
    testing::MixedGridOptions o;
    o.nx = o.ny = o.nz = 4;
    auto mesh = tetrahedralize(testing::make_mixed_grid(o)).value();
    std::vector<double> wave;
    for (const Vec3& p : mesh.points()) wave.push_back(0.5 + 0.45 * std::sin(1.3 * p.x));
    EXPECT_TRUE(mesh.add_point_field(make_double_field("wave", 1, wave)).ok());
    Scene scene;
    SceneVolume v;
    v.mesh = "grid";
    v.tets = std::make_shared<const TetMesh>(std::move(mesh));
    v.scalar = "wave";
    v.transfer_function =
        make_quick_transfer_function("Cool to Warm", 0.05, 0.95, 0.6, 1.5).value();
    scene.volumes.push_back(std::move(v));
    scene.camera = framing_camera(scene.volumes[0].tets->bounds(), kDefaultViewDirection);
    scene.width = 400;
    scene.height = 200;  // wide: room beside the volume
    scene.background = Vec3(0.05, 0.05, 0.1);
    return scene;
}

TEST(Annotations, LegendBesideTheVolumeAndBoxOnTheCorners) {
    const Scene scene = grid_scene();
    Pipeline pipeline;
    auto rendered = pipeline.render(scene);
    ASSERT_TRUE(rendered.ok()) << rendered.error().to_string();
    const Image plain = rendered->image;

    // Nothing asked: nothing drawn.
    Image same = plain;
    AnnotationOptions none;
    none.legend = false;
    ASSERT_TRUE(annotate(same, scene, pipeline, none).ok());
    EXPECT_EQ(same.pixels, plain.pixels);

    Image annotated = plain;
    AnnotationOptions options;
    options.bounding_box = true;
    options.axes = true;
    ASSERT_TRUE(annotate(annotated, scene, pipeline, options).ok());

    // The legend alone, to find its rectangle: it covers no pixel of the volume.
    Image legend_only = plain;
    LegendSpec spec;
    spec.title = "wave";
    spec.background = Vec3f(scene.background);
    auto layout = draw_legend(legend_only, scene.volumes[0].transfer_function, spec);
    ASSERT_TRUE(layout.ok());
    const Vec3f bg(scene.background);
    int volume_under_legend = 0;
    for (int y = layout->whole.y0; y < layout->whole.y1; ++y) {
        for (int x = layout->whole.x0; x < layout->whole.x1; ++x) {
            const Vec3f d = glm::abs(plain.at(x, y) - bg);
            if (std::max({d.x, d.y, d.z}) > 0.5f / 255) ++volume_under_legend;
        }
    }
    EXPECT_EQ(volume_under_legend, 0);
    // annotate drew the same legend (same place, same title: the array's name).
    const int bx = (layout->bar.x0 + layout->bar.x1) / 2;
    for (int y = layout->bar.y0; y < layout->bar.y1; ++y) {
        ASSERT_EQ(annotated.at(bx, y), legend_only.at(bx, y)) << y;
    }

    // Box corners on the pixels the camera projects them to.
    const Bounds3 b = scene.volumes[0].tets->bounds();
    const CameraFrame frame(scene.camera, scene.width, scene.height);
    int corners = 0;
    for (int i = 0; i < 8; ++i) {
        const Vec3 c(i & 1 ? b.hi.x : b.lo.x, i & 2 ? b.hi.y : b.lo.y, i & 4 ? b.hi.z : b.lo.z);
        const Vec3 p = frame.project(c);
        if (p.x < 0 || p.y < 0 || p.x >= scene.width || p.y >= scene.height) continue;
        EXPECT_EQ(annotated.at(int(p.x), int(p.y)), options.box_color) << "corner " << i;
        ++corners;
    }
    EXPECT_EQ(corners, 8);
}

TEST(Annotations, ALegendPerVolumeEachOffTheOthers) {
    Scene scene = grid_scene();
    SceneVolume second = scene.volumes[0];
    second.scalar = "other";
    second.transfer_function = make_quick_transfer_function("Jet", -5.0, 5.0, 0.5, 1.0).value();
    scene.volumes.push_back(second);
    Pipeline pipeline;  // nothing loaded: no bounding box asked
    Image annotated(scene.width, scene.height, Vec3f(scene.background));
    ASSERT_TRUE(annotate(annotated, scene, pipeline, AnnotationOptions{}).ok());
    // The same as drawing the two legends one after the other; they do not overlap.
    Image expected(scene.width, scene.height, Vec3f(scene.background));
    LegendSpec spec;
    spec.background = Vec3f(scene.background);
    spec.title = "wave";
    auto first = draw_legend(expected, scene.volumes[0].transfer_function, spec);
    spec.title = "other";
    auto other = draw_legend(expected, scene.volumes[1].transfer_function, spec);
    ASSERT_TRUE(first.ok() && other.ok());
    EXPECT_EQ(annotated.pixels, expected.pixels);
    const PixelRect& a = first->whole;
    const PixelRect& b = other->whole;
    EXPECT_TRUE(a.x1 <= b.x0 || b.x1 <= a.x0 || a.y1 <= b.y0 || b.y1 <= a.y0);
    // Volume 0's only, when asked.
    Image one(scene.width, scene.height, Vec3f(scene.background));
    AnnotationOptions only_first;
    only_first.every_volume = false;
    ASSERT_TRUE(annotate(one, scene, pipeline, only_first).ok());
    EXPECT_NE(one.pixels, annotated.pixels);
}

TEST(Annotations, AVolumeMadeWithALogScaleGetsALogAxis) {
    Scene scene = grid_scene();
    SceneVolume& v = scene.volumes[0];
    v.transfer_function =
        log_scaled(make_quick_transfer_function("Cool to Warm", -2.0, 2.0, 0.6, 1.5).value())
            .value();
    v.log_scale = true;
    Pipeline pipeline;
    Image annotated(scene.width, scene.height, Vec3f(scene.background));
    ASSERT_TRUE(annotate(annotated, scene, pipeline, AnnotationOptions{}).ok());
    Image expected(scene.width, scene.height, Vec3f(scene.background));
    LegendSpec spec;
    spec.background = Vec3f(scene.background);
    spec.title = "wave";
    spec.log_scale = true;
    const auto layout = draw_legend(expected, v.transfer_function, spec);
    ASSERT_TRUE(layout.ok());
    EXPECT_EQ(annotated.pixels, expected.pixels);
    // Ticks at the decades, 0.1 at a quarter of the bar (log10 -1 of -2 .. 2), and the bar's
    // colours there those of the map's quarter.
    const std::vector<double> decades = {0.01, 0.1, 1.0, 10.0, 100.0};
    ASSERT_EQ(layout->ticks.size(), decades.size());
    for (std::size_t i = 0; i < decades.size(); ++i) {
        EXPECT_NEAR(layout->ticks[i], decades[i], 1e-12 * decades[i]);
    }
    const TransferFunction map =
        make_quick_transfer_function("Cool to Warm", -2.0, 2.0, 0.6, 1.5).value();
    const int row = layout->row_of(0.1);
    const Vec3f shown = annotated.at((layout->bar.x0 + layout->bar.x1) / 2, row);
    const Vec3 want = map.color(std::log10(layout->value_at_row(row)));
    EXPECT_LT(std::abs(shown.x - want.x) + std::abs(shown.y - want.y) + std::abs(shown.z - want.z),
              3e-3);
    // Linear, the same transfer function's legend differs.
    v.log_scale = false;
    Image linear(scene.width, scene.height, Vec3f(scene.background));
    ASSERT_TRUE(annotate(linear, scene, pipeline, AnnotationOptions{}).ok());
    EXPECT_NE(linear.pixels, annotated.pixels);
}

TEST(Annotations, WrongSizeIsAnError) {
    const Scene scene = grid_scene();
    Pipeline pipeline;
    Image image(10, 10);
    const Status status = annotate(image, scene, pipeline, AnnotationOptions{});
    ASSERT_FALSE(status.ok());
    EXPECT_NE(status.error().message.find("10x10"), std::string::npos);
}

}  // namespace
}  // namespace tr
