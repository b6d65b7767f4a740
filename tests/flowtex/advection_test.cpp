// Texture advection against closed forms: uniform flow shifts the picture by v k dt, rigid
// rotation turns the texture coordinates by omega k dt, the double gyre's transport solution
// matches independent backward RK4 traces and its forward points follow particle paths,
// backward and forward methods agree, re-injection's schedule, slices of a mesh follow its
// field, advect_frames. Measured values are in the comments next to each bound.
#include <flowtex/advect_frames.h>
#include <flowtex/advection.h>
#include <flowtex/flow.h>
#include <flowtex/sheet.h>
#include <flowtex/sheet_raster.h>
#include <tests/flowtex/fixtures.h>
#include <tests/support/image_shift.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace tr {
namespace {

using testing::mesh_with_field;
using testing::MeshFixture;
using testing::source_point;
using testing::square_sheet;
using testing::top_view;

TEST(TextureAdvection, UniformFlowShiftsThePictureByVKdt) {
    const Sheet sheet = square_sheet(-1.5, 60, 0.05);
    const AnalyticFlow flow = uniform_flow(Vec3(0.3, 0.2, 0.0));
    const PeriodicTexture tex = PeriodicTexture::filtered_noise(64, 11, 2);
    const CameraFrame frame = top_view(128);
    for (const AdvectionMethod method : {AdvectionMethod::kBackward, AdvectionMethod::kForward}) {
        AdvectionOptions o;
        o.dt = 0.05;
        o.texture_period = 1.0;  // 64 texels over 64 pixels
        o.method = method;
        TextureAdvection adv = TextureAdvection::create(sheet, flow, o).value();
        const std::vector<float> frame0 = rasterize_sheet_values(frame, adv.views(), tex);
        double worst = 0;
        for (int k = 1; k <= 20; ++k) {
            adv.advance();
            if (k % 5 != 0) continue;
            const std::vector<float> frame_k = rasterize_sheet_values(frame, adv.views(), tex);
            // World v k dt in pixels: 64 px per unit, image y downwards.
            const glm::dvec2 expected(0.3 * k * 0.05 * 64, -0.2 * k * 0.05 * 64);
            const auto est = testing::estimate_shift(frame0, frame_k, 128, 128, expected, 3, 4);
            const double error = glm::length(est.shift - expected);
            worst = std::max(worst, error);
            std::printf(
                "method %d frame %d: expected (%.3f, %.3f) px, found (%.3f, %.3f), peak "
                "%.4f\n",
                static_cast<int>(method), k, expected.x, expected.y, est.shift.x, est.shift.y,
                est.peak);
            EXPECT_GT(est.peak, 0.98);  // measured 0.9901..0.9977
        }
        // Measured: largest error 0.0184 px for both methods (frames 5..20, shifts up to
        // 23 px; the parabola fit's bias); bound 0.0184 x 1.5 of a pixel.
        EXPECT_LT(worst, 0.0184 * 1.5) << "method " << static_cast<int>(method);
    }
}

TEST(TextureAdvection, RigidRotationTurnsTheTextureCoordinatesByOmegaKdt) {
    // The seed's steady method: each point's source Q moves one RK4 step further back along its
    // streamline per frame, so Q(P, k dt) = R(-omega k dt) P up to RK4's error.
    const Sheet sheet = square_sheet(-1.0, 40, 0.05);
    const double omega = 0.7, dt = 0.05;
    const AnalyticFlow flow = rigid_rotation(Vec3(0.0), omega);
    AdvectionOptions o;
    o.dt = dt;
    o.texture_period = 0.5;
    TextureAdvection adv = TextureAdvection::create(sheet, flow, o).value();
    const int frames = 60;
    for (int k = 0; k < frames; ++k) adv.advance();
    const double angle = -omega * frames * dt;
    double worst = 0;
    for (std::size_t i = 0; i < sheet.points.size(); ++i) {
        const Vec3& p = sheet.points[i];
        const glm::dvec2 expected(std::cos(angle) * p.x - std::sin(angle) * p.y,
                                  std::sin(angle) * p.x + std::cos(angle) * p.y);
        worst = std::max(worst,
                         glm::length(source_point(adv, sheet, 0, i, o.texture_period) - expected));
    }
    std::printf("rotation: largest error %.3g\n", worst);
    EXPECT_LT(worst, 3.7e-8 * 1.5);  // measured 3.71e-8 (60 RK4 steps of 0.035 rad)
}

TEST(TextureAdvection, DoubleGyreTransportMatchesBackwardRk4Traces) {
    // Unsteady flow, method 1 of the seed's [28]: Q(P, t) solved frame to frame on the sheet.
    // Reference: each point traced back from t to 0 by RK4 in steps of dt / 10, independently.
    const Sheet sheet =
        grid_sheet(Vec3(0.0), Vec3(1, 0, 0), Vec3(0, 1, 0), 128, 64, 1.0 / 64).value();
    const AnalyticFlow flow = double_gyre();
    ASSERT_FALSE(flow.steady());
    AdvectionOptions o;
    o.dt = 0.1;
    o.texture_period = 1.0;
    TextureAdvection adv = TextureAdvection::create(sheet, flow, o).value();
    const int frames = 20;
    for (int k = 0; k < frames; ++k) adv.advance();
    const double t_end = frames * o.dt;
    double worst = 0, sum_sq = 0;
    for (std::size_t i = 0; i < sheet.points.size(); ++i) {
        Vec3 q = sheet.points[i];
        CellId hint = kNoCell;
        const int substeps = 10 * frames;
        const double h = t_end / substeps;
        for (int s = 0; s < substeps; ++s) {
            const auto back = rk4_step(flow, q, t_end - s * h, -h, Vec3(0, 0, 1), hint);
            ASSERT_TRUE(back.has_value());
            q = *back;
        }
        const double e =
            glm::length(source_point(adv, sheet, 0, i, o.texture_period) - glm::dvec2(q.x, q.y));
        worst = std::max(worst, e);
        sum_sq += e * e;
    }
    const double rms = std::sqrt(sum_sq / sheet.points.size());
    std::printf("double gyre, t = %.1f: largest error %.3g, rms %.3g (sheet spacing %.4f)\n", t_end,
                worst, rms, sheet.spacing);
    // Measured: largest 0.0125 (0.8 of the sheet's spacing, where the gyres stretch Q most),
    // rms 0.00279; bounds x1.25.
    EXPECT_LT(worst, 0.0125 * 1.25);
    EXPECT_LT(rms, 0.00279 * 1.25);
}

TEST(TextureAdvection, DoubleGyreForwardPointsFollowParticlePaths) {
    // Unsteady flow, method 2 of [28]: the points move along particle paths. Reference: each
    // point traced forward from 0 to t independently by RK4 in steps of dt / 10.
    const Sheet sheet =
        grid_sheet(Vec3(0.0), Vec3(1, 0, 0), Vec3(0, 1, 0), 64, 32, 1.0 / 32).value();
    const AnalyticFlow flow = double_gyre();
    AdvectionOptions o;
    o.dt = 0.1;
    o.method = AdvectionMethod::kForward;
    TextureAdvection adv = TextureAdvection::create(sheet, flow, o).value();
    const int frames = 20;
    for (int k = 0; k < frames; ++k) adv.advance();
    double worst = 0;
    for (std::size_t i = 0; i < sheet.points.size(); ++i) {
        Vec3 p = sheet.points[i];
        CellId hint = kNoCell;
        const double h = o.dt / 10;
        for (int s = 0; s < 10 * frames; ++s) {
            p = rk4_step(flow, p, s * h, h, Vec3(0, 0, 1), hint).value();
        }
        worst = std::max(worst, glm::length(adv.positions(0)[i] - p));
        // Texture coordinates never change in the forward method.
        EXPECT_EQ(adv.texcoords(0)[i], sheet.plane_coordinates(sheet.points[i]));
    }
    std::printf("double gyre forward: largest difference from the fine trace %.3g\n", worst);
    EXPECT_LT(worst, 1.33e-6 * 1.5);  // measured 1.33e-6 (RK4 at dt 0.1 against dt 0.01)
}

TEST(TextureAdvection, BackwardAndForwardAgreeOnASteadyFlow) {
    // Rigid rotation: backward draws tex(Q(x)) at the fixed points, forward draws the moved
    // points with their first coordinates; both are tex(R(-omega t) x) where both cover x.
    const Sheet sheet = square_sheet(-1.0, 40, 0.05);
    const AnalyticFlow flow = rigid_rotation(Vec3(0.0), 0.7);
    const PeriodicTexture tex = PeriodicTexture::filtered_noise(64, 5, 2);
    const CameraFrame frame = top_view(128);
    AdvectionOptions o;
    o.dt = 0.05;
    o.texture_period = 0.5;
    TextureAdvection backward = TextureAdvection::create(sheet, flow, o).value();
    o.method = AdvectionMethod::kForward;
    TextureAdvection forward = TextureAdvection::create(sheet, flow, o).value();
    for (int k = 0; k < 30; ++k) {
        backward.advance();
        forward.advance();
    }
    const std::vector<float> b = rasterize_sheet_values(frame, backward.views(), tex);
    const std::vector<float> f = rasterize_sheet_values(frame, forward.views(), tex);
    double worst = 0;
    std::size_t both = 0;
    for (std::size_t p = 0; p < b.size(); ++p) {
        if (std::isnan(b[p]) || std::isnan(f[p])) continue;
        ++both;
        worst = std::max(worst, static_cast<double>(std::abs(b[p] - f[p])));
    }
    std::printf("backward vs forward: %zu pixels, largest difference %.3g\n", both, worst);
    EXPECT_GT(both, 128u * 128u * 6 / 10);
    // Measured 1.19e-7 over 13860 pixels: both are exact for a rotation (Q is linear in P), so
    // only float rounding differs; bound a few float ulps of 1.
    EXPECT_LT(worst, 5e-7);
}

TEST(TextureAdvection, ReinjectionCrossFadesTwoLayersThatReset) {
    const Sheet sheet = square_sheet(-1.0, 10, 0.2);
    const AnalyticFlow flow = uniform_flow(Vec3(1, 0, 0));
    AdvectionOptions o;
    o.dt = 0.1;
    o.reinject_frames = 8;
    TextureAdvection adv = TextureAdvection::create(sheet, flow, o).value();
    ASSERT_EQ(adv.num_layers(), 2);
    for (int k = 0; k <= 20; ++k) {
        const auto views = adv.views();
        const double age0 = k % 8, age1 = (k + 4) % 8;
        EXPECT_FLOAT_EQ(views[0].weight, 1.0 - std::abs(2.0 * age0 / 8 - 1.0)) << k;
        EXPECT_FLOAT_EQ(views[0].weight + views[1].weight, 1.0f) << k;
        // Layer 0 was reset `age0` frames ago: its sources lie v * age0 * dt upstream.
        const glm::dvec2 q = source_point(adv, sheet, 0, 7, o.texture_period);
        EXPECT_NEAR(q.x, sheet.points[7].x - age0 * 0.1, 1e-12) << k;
        const glm::dvec2 q1 = source_point(adv, sheet, 1, 7, o.texture_period);
        EXPECT_NEAR(q1.x, sheet.points[7].x - (k < 4 ? k : age1) * 0.1, 1e-12) << k;
        adv.advance();
    }
    o.reinject_frames = 3;
    EXPECT_FALSE(TextureAdvection::create(sheet, flow, o).ok());
    o.reinject_frames = 0;
    o.dt = 0;
    EXPECT_FALSE(TextureAdvection::create(sheet, flow, o).ok());
}

TEST(TextureAdvection, SliceOfAMeshFollowsItsFieldInThePlane) {
    const MeshFixture f = mesh_with_field(glm::dmat3(0.0), Vec3(0.5, 0.25, 0.3));
    const VelocityField velocity = VelocityField::steady(f.mesh, f.field).value();
    const MeshFlow flow(f.mesh, f.adjacency, velocity);
    const Sheet sheet =
        slice_sheet(flow.locator(), f.mesh.bounds(), Vec3(0, 0, 0.1), Vec3(0, 0, 2), 32).value();
    EXPECT_EQ(sheet.points.size(), 33u * 33u);  // the whole square: the mesh is a box
    EXPECT_EQ(sheet.triangles.size(), 2u * 32 * 32);
    AdvectionOptions o;
    o.dt = 0.1;
    TextureAdvection adv = TextureAdvection::create(sheet, flow, o).value();
    for (int k = 0; k < 10; ++k) adv.advance();
    // The in-plane velocity (0.5, 0.25) for t = 1; the z component is dropped.
    double worst = 0;
    int compared = 0;
    for (std::size_t i = 0; i < sheet.points.size(); ++i) {
        const Vec3& p = sheet.points[i];
        EXPECT_DOUBLE_EQ(p.z, 0.1);
        const glm::dvec2 expected(p.x - 0.5, p.y - 0.25);
        if (expected.x < -2 || expected.y < -2) continue;  // its streamline enters at the side
        const glm::dvec2 st = (adv.texcoords(0)[i]) * o.texture_period;
        const Vec3 q = sheet.origin + st.x * sheet.axis_u + st.y * sheet.axis_v;
        worst = std::max(worst, glm::length(glm::dvec2(q.x, q.y) - expected));
        EXPECT_NEAR(q.z, 0.1, 1e-12);
        ++compared;
    }
    std::printf("slice: %d points compared, largest error %.3g\n", compared, worst);
    EXPECT_GT(compared, 700);
    EXPECT_LT(worst, 1e-12);  // measured 9.9e-16 (0.5 and 0.25 are exact floats; rounding)
}

TEST(TextureAdvectionBadInput, SliceMissingTheMeshAndZeroVelocity) {
    const MeshFixture f = mesh_with_field(glm::dmat3(0.0), Vec3(0.0));
    const VelocityField velocity = VelocityField::steady(f.mesh, f.field).value();
    const MeshFlow flow(f.mesh, f.adjacency, velocity);
    const auto missed =
        slice_sheet(flow.locator(), f.mesh.bounds(), Vec3(0, 0, 5), Vec3(0, 0, 1), 16);
    ASSERT_FALSE(missed.ok());
    EXPECT_NE(missed.error().message.find("misses the mesh"), std::string::npos)
        << missed.error().message;
    EXPECT_FALSE(slice_sheet(flow.locator(), f.mesh.bounds(), Vec3(0.0), Vec3(0.0), 16).ok());

    // Zero velocity everywhere: still frames, a dt chosen anyway.
    AdvectFramesOptions o;
    o.steps = 3;
    o.width = 48;
    o.height = 32;
    o.sheet_resolution = 24;
    std::vector<Image> frames;
    const auto report =
        advect_frames(f.mesh, f.adjacency, velocity, o, [&](int, const Image& picture) -> Status {
            frames.push_back(picture);
            return {};
        });
    ASSERT_TRUE(report.ok()) << report.error().to_string();
    EXPECT_EQ(report->frames, 4);
    EXPECT_EQ(report->mean_speed, 0.0);
    EXPECT_EQ(report->dt, 1.0);
    ASSERT_EQ(frames.size(), 4u);
    EXPECT_EQ(max_abs_difference(frames[0], frames[3]), 0.0);
}

TEST(AdvectFrames, RotatingFieldMovesTheTextureAndStopsOnAFailedWrite) {
    // v = (-y, x, 0) about the z axis.
    const MeshFixture f = mesh_with_field(glm::dmat3(0, 1, 0, -1, 0, 0, 0, 0, 0), Vec3(0.0));
    const VelocityField velocity = VelocityField::steady(f.mesh, f.field).value();
    AdvectFramesOptions o;
    o.steps = 6;
    o.width = 64;
    o.height = 64;
    o.sheet_resolution = 32;
    o.slice_normal = Vec3(0, 0, 1);
    std::vector<Image> frames;
    auto keep = [&](int, const Image& picture) -> Status {
        frames.push_back(picture);
        return {};
    };
    for (const AdvectionMethod method : {AdvectionMethod::kBackward, AdvectionMethod::kForward}) {
        frames.clear();
        o.method = method;
        const auto report = advect_frames(f.mesh, f.adjacency, velocity, o, keep);
        ASSERT_TRUE(report.ok()) << report.error().to_string();
        EXPECT_EQ(report->sheet_points, 33u * 33u);
        ASSERT_EQ(frames.size(), 7u);
        // The square slice fills the square picture but its 2% margin; it moved.
        EXPECT_GT(max_abs_difference(frames[0], frames[6]), 0.2);
        const ImageComparison c = compare_images(frames[6], frames[0], Vec3f(0.0f));
        std::printf("method %d: psnr frame 6 vs 0 %.1f dB\n", static_cast<int>(method),
                    c.psnr_foreground);
    }
    int calls = 0;
    const auto failed =
        advect_frames(f.mesh, f.adjacency, velocity, o, [&](int frame, const Image&) -> Status {
            ++calls;
            if (frame == 2) {
                return make_error(ErrorCode::kIo, "disk full");
            }
            return {};
        });
    ASSERT_FALSE(failed.ok());
    EXPECT_EQ(calls, 3);
}

}  // namespace
}  // namespace tr
