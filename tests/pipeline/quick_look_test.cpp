// The quick look's automatic choices (pipeline/quick_look.h) against closed forms.
#include <mesh/tetrahedralize.h>
#include <pipeline/movie.h>
#include <pipeline/quick_look.h>
#include <pipeline/quick_scene.h>
#include <project/colormap.h>
#include <tests/support/mixed_grid.h>

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace tr {
namespace {

TetMesh box_mesh(const Vec3& size, int n = 4) {
    testing::MixedGridOptions grid;
    grid.nx = grid.ny = grid.nz = n;
    grid.linear = glm::dmat3(size.x / n, 0, 0, 0, size.y / n, 0, 0, 0, size.z / n);
    return tetrahedralize(testing::make_mixed_grid(grid)).value();
}

TEST(RobustRange, PercentilesOfAKnownSequence) {
    std::vector<float> values;
    for (int i = 0; i <= 1000; ++i) values.push_back(static_cast<float>(i));
    values.push_back(1e9f);  // one spike
    values.push_back(std::nanf(""));
    const auto whole = robust_range(values, 0.0).value();
    EXPECT_EQ(whole[0], 0.0);
    EXPECT_EQ(whole[1], 1e9);
    // 1002 finite values: the 1st percentile is the 10th smallest, the 99th the 991st.
    const auto robust = robust_range(values, 1.0).value();
    EXPECT_EQ(robust[0], 10.0);
    EXPECT_EQ(robust[1], 991.0);
    EXPECT_FALSE(robust_range(std::vector<float>{std::nanf("")}, 1.0).ok());
}

TEST(MeanChordLength, IsFourVolumeOverAreaOfABox) {
    // 2 x 1 x 0.5: V = 1, S = 2 (2 + 1 + 0.5) = 7.
    EXPECT_NEAR(mean_chord_length(box_mesh({2.0, 1.0, 0.5})), 4.0 / 7.0, 1e-12);
    EXPECT_NEAR(mean_chord_length(box_mesh({1.0, 1.0, 1.0}, 3)), 4.0 / 6.0, 1e-12);
}

TEST(UnitDistanceForOpacity, BringsTheMeanChordToTheTarget) {
    const std::vector<float> values = {0.0f, 1.0f, 1.0f, 0.5f};
    const auto opacity = [](double s) { return 0.2 + 0.4 * s; };
    const double chord = 3.0, target = 0.8;
    const double unit = unit_distance_for_opacity(values, opacity, chord, target);
    double depth = 0.0;  // the mean optical depth over the chord with that unit
    for (float v : values) depth += -std::log(1.0 - opacity(v)) / unit * chord / values.size();
    EXPECT_NEAR(1.0 - std::exp(-depth), target, 1e-12);
    EXPECT_EQ(unit_distance_for_opacity(
                  values, [](double) { return 0.0; }, chord, target),
              0.0);
}

// A box whose field spans 10^-3 .. 10^3 along x, with `zeros` points set to 0.
TetMesh decades_mesh(int zeros) {
    TetMesh mesh = box_mesh({1.0, 1.0, 1.0}, 6);
    Field f;
    f.name = "p";
    std::vector<float> values;
    for (const Vec3& p : mesh.points()) {
        values.push_back(static_cast<float>(std::pow(10.0, -3.0 + 6.0 * p.x)));
    }
    for (int i = 0; i < zeros; ++i) values[static_cast<std::size_t>(i)] = 0.0f;
    f.values = values;
    EXPECT_TRUE(mesh.add_point_field(std::move(f)).ok());
    return mesh;
}

TEST(QuickScene, LogSpreadsTheColourMapOverTheDecades) {
    const TetMesh mesh = decades_mesh(3);
    QuickSceneOptions options;
    options.scalar = "p";
    options.range_percent = 0.0;
    options.log_scale = true;
    std::vector<std::string> notes;
    const Scene scene = make_quick_scene("decades.vtu", mesh, options, {}, &notes).value();
    const SceneVolume& volume = scene.volumes[0];
    EXPECT_TRUE(volume.log_scale);
    const TransferFunction& tf = volume.transfer_function;
    // The map's middle at 1 (the middle decade), its ends at 1e-3 and 1e3.
    const TransferFunction map = make_quick_transfer_function("viridis", -3, 3, 0.5, 1).value();
    for (double x : {-3.0, -1.5, 0.0, 2.0, 3.0}) {
        const Vec3 d = tf.color(std::pow(10.0, x)) - map.color(x);
        EXPECT_LT(std::max({std::abs(d.r), std::abs(d.g), std::abs(d.b)}), 1e-3) << x;
    }
    // The opacity ramp, a fifth of its top at the bottom, is linear in the decades too.
    EXPECT_NEAR(tf.opacity(1e-3), 0.1, 1e-6);
    EXPECT_NEAR(tf.opacity(1.0), 0.3, 1e-3);
    EXPECT_NEAR(tf.opacity(1e3), 0.5, 1e-6);
    // Zeros take the low end, and a note counts them.
    EXPECT_EQ(tf.color(0.0), tf.color(1e-3));
    ASSERT_FALSE(notes.empty());
    EXPECT_NE(notes[0].find("3 of " + std::to_string(mesh.num_points())), std::string::npos)
        << notes[0];
    // Without --log the same field is nearly all the map's low end: 1 sits at 0.1% of it.
    options.log_scale = false;
    const Scene linear = make_quick_scene("decades.vtu", mesh, options).value();
    EXPECT_FALSE(linear.volumes[0].log_scale);
    const Vec3 low = map.color(-3.0), at_one = linear.volumes[0].transfer_function.color(1.0);
    EXPECT_LT(std::abs(at_one.g - low.g), 0.01);
}

TEST(QuickScene, LogRefusesARangeWithoutPositiveValues) {
    QuickSceneOptions options;
    options.scalar = "p";
    options.log_scale = true;
    const TetMesh mesh = decades_mesh(0);
    options.range = std::array<double, 2>{0.0, 10.0};
    const auto zero_start = make_quick_scene("decades.vtu", mesh, options);
    ASSERT_FALSE(zero_start.ok());
    EXPECT_NE(zero_start.error().message.find("--log needs a positive range"), std::string::npos);
    options.range.reset();
    const TetMesh all_zero = decades_mesh(static_cast<int>(mesh.num_points()));
    const auto none = make_quick_scene("decades.vtu", all_zero, options);
    ASSERT_FALSE(none.ok());
    EXPECT_NE(none.error().message.find("has no positive value"), std::string::npos)
        << none.error().message;
    // A positive range given is used in decades: 1e-2 .. 1e2 puts the map's middle at 1.
    options.range = std::array<double, 2>{1e-2, 1e2};
    const Scene scene = make_quick_scene("decades.vtu", mesh, options).value();
    const TransferFunction map = make_quick_transfer_function("viridis", -2, 2, 0.5, 1).value();
    const Vec3 d = scene.volumes[0].transfer_function.color(1.0) - map.color(0.0);
    EXPECT_LT(std::max({std::abs(d.r), std::abs(d.g), std::abs(d.b)}), 1e-3);
}

// Every point inside the picture with the margin free, the extent centred and touching the
// margin on one pair of sides.
void expect_fits(const TetMesh& mesh, const CameraFit& fit) {
    const Camera camera = fitting_camera(std::vector<const TetMesh*>{&mesh}, fit);
    const CameraFrame frame(camera, fit.width, fit.height);
    double x_lo = 1e300, x_hi = -1e300, y_lo = 1e300, y_hi = -1e300;
    for (const Vec3& p : mesh.points()) {
        const Vec3 s = frame.project(p);
        ASSERT_GT(s.z, 0.0);
        x_lo = std::min(x_lo, s.x), x_hi = std::max(x_hi, s.x);
        y_lo = std::min(y_lo, s.y), y_hi = std::max(y_hi, s.y);
    }
    const double mx = fit.margin * fit.width, my = fit.margin * fit.height;
    const double slack = 1e-6;
    EXPECT_GE(x_lo, mx - slack);
    EXPECT_LE(x_hi, fit.width - mx + slack);
    EXPECT_GE(y_lo, my - slack);
    EXPECT_LE(y_hi, fit.height - my + slack);
    // Centred to a small fraction of the picture (one refinement under perspective: measured
    // offsets below 0.01% of the side on these boxes).
    EXPECT_NEAR(x_lo + x_hi, fit.width, 0.001 * fit.width);
    EXPECT_NEAR(y_lo + y_hi, fit.height, 0.001 * fit.height);
    // Tight: one pair of sides within 2% of the picture of its margin.
    const bool wide = x_lo < mx + 0.02 * fit.width && x_hi > fit.width - mx - 0.02 * fit.width;
    const bool tall = y_lo < my + 0.02 * fit.height && y_hi > fit.height - my - 0.02 * fit.height;
    EXPECT_TRUE(wide || tall) << x_lo << " " << x_hi << " " << y_lo << " " << y_hi;
}

TEST(FittingCamera, FitsTheProjectedExtentOfAThinPlate) {
    const TetMesh plate = box_mesh({4.0, 1.0, 0.1});
    CameraFit fit;
    expect_fits(plate, fit);
    fit.width = 300, fit.height = 600;
    expect_fits(plate, fit);
    fit.azimuth = 40, fit.elevation = 30;
    expect_fits(plate, fit);
    fit.from = Vec3(0, 0, 1);
    expect_fits(plate, fit);
}

TEST(FittingCamera, ZoomNarrowsTheViewAngleAndElevationRaisesTheEye) {
    const TetMesh cube = box_mesh({1.0, 1.0, 1.0}, 2);
    CameraFit fit;
    fit.from = Vec3(1, 0, 0);
    fit.zoom = 2.0;
    const Camera zoomed = fitting_camera(std::vector<const TetMesh*>{&cube}, fit);
    EXPECT_DOUBLE_EQ(zoomed.view_angle, 15.0);
    fit.zoom = 1.0;
    fit.elevation = 30.0;
    const Camera raised = fitting_camera(std::vector<const TetMesh*>{&cube}, fit);
    const Vec3 d = glm::normalize(raised.position - raised.focal_point);
    EXPECT_NEAR(std::asin(d.z) * 180.0 / std::numbers::pi, 30.0, 1e-9);
    EXPECT_EQ(raised.view_up, Vec3(0, 0, 1));
}

TEST(OrbitCameras, TurnAboutTheUpAxisWithoutRolling) {
    Camera start;
    start.position = Vec3(3, -4, 2);
    start.focal_point = Vec3(1, 1, 1);
    start.view_up = Vec3(0, 0, 2);
    const auto cameras = orbit_cameras(start, 360.0, 8);
    ASSERT_EQ(cameras.size(), 8u);
    EXPECT_EQ(cameras[0].position, start.position);
    for (std::size_t k = 0; k < cameras.size(); ++k) {
        const Vec3 now = cameras[k].position - start.focal_point;
        const Vec3 then = start.position - start.focal_point;
        EXPECT_EQ(cameras[k].view_up, start.view_up);
        EXPECT_NEAR(now.z, then.z, 1e-12);  // the same height along the axis
        // Turned by 45 degrees a frame, anticlockwise seen from above.
        const double angle = std::atan2(now.y, now.x) - std::atan2(then.y, then.x);
        EXPECT_NEAR(std::remainder(angle - k * std::numbers::pi / 4, 2 * std::numbers::pi), 0.0,
                    1e-12);
        EXPECT_NEAR(glm::length(Vec3(now.x, now.y, 0)), glm::length(Vec3(then.x, then.y, 0)),
                    1e-12);
    }
}

TEST(AnimationFrames, AnOrbitsCamerasOrASplatCyclesFramesInOrder) {
    Pipeline pipeline;
    Scene scene;
    scene.camera.position = Vec3(0, -5, 1);
    AnimationSpec orbit;
    orbit.orbit_degrees = 90;
    orbit.orbit_frames = 3;
    const auto cameras = orbit_cameras(scene.camera, 90, 3);
    std::vector<int> seen;
    auto count = for_each_animation_frame(pipeline, scene, orbit, [&](int k, const Scene& view) {
        seen.push_back(k);
        EXPECT_EQ(view.camera.position, cameras[static_cast<std::size_t>(k)].position);
        return Status{};
    });
    ASSERT_TRUE(count.ok());
    EXPECT_EQ(*count, 3);
    EXPECT_EQ(seen, (std::vector<int>{0, 1, 2}));
    AnimationSpec cycle;
    cycle.splat_cycle = 4;
    seen.clear();
    count = for_each_animation_frame(pipeline, scene, cycle, [&](int k, const Scene& view) {
        seen.push_back(static_cast<int>(std::get<std::int64_t>(view.method->options.at("frame"))));
        EXPECT_EQ(view.camera.position, scene.camera.position);
        return k == 2 ? Status(make_error(ErrorCode::kIo, "disk full")) : Status{};
    });
    // The third frame's error stops the animation and is returned.
    ASSERT_FALSE(count.ok());
    EXPECT_EQ(count.error().message, "disk full");
    EXPECT_EQ(seen, (std::vector<int>{0, 1, 2}));
}

// A series whose field is zero at its first step: the range comes from every step, and the
// field is called constant only when it is over the whole series.
TEST(QuickSceneSeries, RangeCoversEveryStepAndConstantMeansOverTheSeries) {
    TetMesh zero = box_mesh({1.0, 1.0, 1.0}, 3), ramp = zero;
    std::vector<float> zeros(zero.num_points(), 0.0f), x;
    for (const Vec3& p : ramp.points()) x.push_back(static_cast<float>(2.0 * p.x));
    ASSERT_TRUE(zero.add_point_field(make_float_field("c", 1, zeros)).ok());
    ASSERT_TRUE(ramp.add_point_field(make_float_field("c", 1, x)).ok());
    QuickSceneOptions options;
    options.scalar = "c";
    options.range_percent = 0.0;  // the whole range: its ends are known
    const auto range_of = [](const Scene& scene) {
        const auto& points = scene.volumes[0].transfer_function.color_points();
        return std::array<double, 2>{points.front().s, points.back().s};
    };
    std::vector<std::string> notes;
    // Step 0 alone: a constant, drawn over a made-up range around it.
    const Scene alone = make_quick_scene("zero.vtu", zero, options, {}, &notes).value();
    EXPECT_EQ(range_of(alone), (std::array<double, 2>{-0.5, 0.5}));
    ASSERT_EQ(notes.size(), 1u);
    EXPECT_NE(notes[0].find("is constant (0"), std::string::npos) << notes[0];
    // With the next step: the series' range, no note.
    notes.clear();
    options.series = {&ramp};
    const Scene series = make_quick_scene("zero.vtu", zero, options, {}, &notes).value();
    EXPECT_EQ(range_of(series), (std::array<double, 2>{0.0, 2.0}));
    EXPECT_TRUE(notes.empty()) << notes[0];
    // Zero at every step: constant over the series, said so.
    options.series = {&zero, &zero};
    (void)make_quick_scene("zero.vtu", zero, options, {}, &notes).value();
    ASSERT_EQ(notes.size(), 1u);
    EXPECT_NE(notes[0].find("is constant over all 3 time steps"), std::string::npos) << notes[0];
}

}  // namespace
}  // namespace tr
