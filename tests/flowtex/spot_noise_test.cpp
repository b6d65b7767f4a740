// Spot noise against closed forms: on the mesh fixture over [-2, 2]^3 with the scalar s = z
// (linear, so the band |z - iso| < band is exact), every spot centre lies in the band in every
// frame; in uniform flow a spot not reseeded moves by exactly v dt; in rigid rotation about z
// the density over the disk r < 1.8 stays even (equal-area bins); each isolated spot's ellipse
// points along its projected velocity (image moments); bad input; zero velocity gives still
// frames; opaque geometry in front hides the spots. Measured values next to each bound.
#include <core/parallel.h>
#include <flowtex/flow.h>
#include <flowtex/spot_noise.h>
#include <flowtex/spot_noise_frames.h>
#include <flowtex/spot_raster.h>
#include <tests/flowtex/fixtures.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace tr {
namespace {

using testing::mesh_with_field;
using testing::MeshFixture;

constexpr double kPi = 3.14159265358979323846;

// The fixture with v = a p + b and the point scalar "z" = z.
MeshFixture fixture(const glm::dmat3& a, const Vec3& b) {
    MeshFixture f = mesh_with_field(a, b);
    std::vector<float> z;
    for (const Vec3& p : f.mesh.points()) z.push_back(static_cast<float>(p.z));
    EXPECT_TRUE(f.mesh.add_point_field(make_float_field("z", 1, z)).ok());
    return f;
}

const Field& z_field(const MeshFixture& f) { return *find_field(f.mesh.point_fields(), "z"); }

glm::dmat3 rotation_matrix(double omega) {
    glm::dmat3 a(0.0);
    a[1][0] = -omega;  // v.x = -omega y
    a[0][1] = omega;   // v.y = omega x
    return a;
}

// Spots in the band |z| < band of the fixture turning about z at 1 radian per unit time (built
// in place: the locator, velocity and flow point into the fixture).
struct RotatingBand {
    MeshFixture f = fixture(rotation_matrix(1.0), Vec3(0.0));
    PointLocator locator{f.mesh, f.adjacency};
    VelocityField velocity = VelocityField::steady(f.mesh, f.field).value();
    MeshFlow flow{f.mesh, f.adjacency, velocity};

    SpotNoise spots(double band, std::size_t count) const {
        SpotNoiseOptions o;
        o.iso = 0.0;
        o.band = band;
        o.count = count;
        return SpotNoise::create(f.mesh, locator, z_field(f), flow, o).value();
    }
};

TEST(SpotNoise, EveryCentreLiesInTheBandInEveryFrame) {
    // The flow crosses the band (v.z != 0) and leaves the box: spots are reseeded every frame.
    const MeshFixture f = fixture(glm::dmat3(0.0), Vec3(0.5, 0.3, 0.2));
    const PointLocator locator(f.mesh, f.adjacency);
    const VelocityField velocity = VelocityField::steady(f.mesh, f.field).value();
    const MeshFlow flow(f.mesh, f.adjacency, velocity);
    SpotNoiseOptions o;
    o.iso = 0.3;
    o.band = 0.2;
    o.count = 5000;
    o.dt = 0.1;
    SpotNoise spots = SpotNoise::create(f.mesh, locator, z_field(f), flow, o).value();
    std::size_t reseeded = 0;
    double widest = 0;
    for (int k = 0; k <= 30; ++k) {
        if (k > 0) {
            spots.advance();
            reseeded += spots.reseeded();
        }
        ASSERT_EQ(spots.size(), 5000u);
        std::size_t in_band = 0;
        for (const Vec3& p : spots.positions()) {
            // The scalar at the centre, from its closed form (s = z, |grad s| = 1).
            widest = std::max(widest, std::abs(p.z - 0.3));
            in_band += std::abs(p.z - 0.3) < 0.2 && std::abs(p.x) <= 2 && std::abs(p.y) <= 2;
        }
        EXPECT_EQ(in_band, 5000u) << "frame " << k;
    }
    std::printf("widest |z - iso| %.6f (band 0.2); reseeded %zu over 30 frames\n", widest,
                reseeded);
    // The test means something only if spots left the band and came back.
    EXPECT_GT(reseeded, 1000u);
}

TEST(SpotNoise, UniformFlowMovesSpotsByVdt) {
    const Vec3 v(0.6, 0.25, 0.0);
    const MeshFixture f = fixture(glm::dmat3(0.0), v);
    const PointLocator locator(f.mesh, f.adjacency);
    const VelocityField velocity = VelocityField::steady(f.mesh, f.field).value();
    const MeshFlow mesh_flow(f.mesh, f.adjacency, velocity);
    const AnalyticFlow analytic = uniform_flow(v);
    for (const Flow* flow :
         {static_cast<const Flow*>(&mesh_flow), static_cast<const Flow*>(&analytic)}) {
        SpotNoiseOptions o;
        o.iso = -0.5;
        o.band = 0.1;
        o.count = 3000;
        o.dt = 0.05;
        SpotNoise spots = SpotNoise::create(f.mesh, locator, z_field(f), *flow, o).value();
        double worst = 0;
        std::size_t moved = 0;
        for (int k = 1; k <= 20; ++k) {
            const std::vector<Vec3> before(spots.positions().begin(), spots.positions().end());
            const std::vector<std::uint32_t> gen(spots.generations().begin(),
                                                 spots.generations().end());
            spots.advance();
            for (std::size_t i = 0; i < spots.size(); ++i) {
                if (spots.generations()[i] != gen[i]) continue;
                worst = std::max(worst, glm::length(spots.positions()[i] - before[i] - v * 0.05));
                ++moved;
            }
        }
        std::printf("%s flow: largest |displacement - v dt| %.3g over %zu moves\n",
                    flow == &analytic ? "analytic" : "mesh", worst, moved);
        EXPECT_GT(moved, 50000u);
        // Measured: 9.5e-17 (analytic: RK4 is exact for constant v), 1.2e-9 (mesh: v stored
        // as float and interpolated); bounds x 10.
        EXPECT_LT(worst, flow == &analytic ? 1e-15 : 1.2e-8);
    }
}

TEST(SpotNoise, UnsteadyFlowMovesSpotsByTheIntegralOfV) {
    // A velocity sampled at t = 0 (b0) and t = 1 (b1), linear in time between: from t0 to t1 a
    // spot moves by b0 (t1 - t0) + (b1 - b0) (t1^2 - t0^2) / 2 (RK4 is exact for it).
    const Vec3 b0(0.6, 0.0, 0.0), b1(0.0, 0.5, 0.1);
    const MeshFixture f = fixture(glm::dmat3(0.0), b0);
    const MeshFixture later = fixture(glm::dmat3(0.0), b1);
    const PointLocator locator(f.mesh, f.adjacency);
    const VelocityField velocity =
        VelocityField::unsteady(f.mesh, {f.field, later.field}, {0.0, 1.0}).value();
    const MeshFlow flow(f.mesh, f.adjacency, velocity);
    ASSERT_FALSE(flow.steady());
    SpotNoiseOptions o;
    o.iso = -0.5;
    o.band = 0.1;
    o.count = 3000;
    o.dt = 0.05;
    SpotNoise spots = SpotNoise::create(f.mesh, locator, z_field(f), flow, o).value();
    double worst = 0;
    std::size_t moved = 0;
    for (int k = 1; k <= 20; ++k) {
        const double t0 = spots.time(), t1 = t0 + o.dt;
        const Vec3 expected = b0 * (t1 - t0) + (b1 - b0) * (0.5 * (t1 * t1 - t0 * t0));
        const std::vector<Vec3> before(spots.positions().begin(), spots.positions().end());
        const std::vector<std::uint32_t> gen(spots.generations().begin(),
                                             spots.generations().end());
        spots.advance();
        EXPECT_NEAR(spots.time(), t1, 1e-12);
        for (std::size_t i = 0; i < spots.size(); ++i) {
            if (spots.generations()[i] != gen[i]) continue;
            worst = std::max(worst, glm::length(spots.positions()[i] - before[i] - expected));
            ++moved;
        }
    }
    std::printf("unsteady flow: largest |displacement - integral of v| %.3g over %zu moves\n",
                worst, moved);
    EXPECT_GT(moved, 40000u);
    // Measured 1.1e-9 (v stored as float, interpolated in space and time); bound x 10.
    EXPECT_LT(worst, 1.2e-8);

    // The frames: the default dt spans the samples' times over the steps.
    SpotNoiseFramesOptions fo;
    fo.scalar = "z";
    fo.spots.iso = -0.5;
    fo.spots.count = 500;
    fo.spots.dt = 0;  // the default
    fo.steps = 4;
    fo.width = fo.height = 32;
    const auto report = spot_noise_frames(f.mesh, f.adjacency, velocity, fo,
                                          [](int, const Image&) { return Status{}; });
    ASSERT_TRUE(report.ok()) << report.error().message;
    EXPECT_DOUBLE_EQ(report->dt, 0.25);
}

TEST(SpotNoise, DensityStaysEvenInRigidRotation) {
    const MeshFixture f = fixture(rotation_matrix(1.0), Vec3(0.0));
    const PointLocator locator(f.mesh, f.adjacency);
    const VelocityField velocity = VelocityField::steady(f.mesh, f.field).value();
    const MeshFlow flow(f.mesh, f.adjacency, velocity);
    SpotNoiseOptions o;
    o.iso = 0.0;
    o.band = 0.25;
    o.count = 20000;
    o.dt = 0.05;
    SpotNoise spots = SpotNoise::create(f.mesh, locator, z_field(f), flow, o).value();
    // 6 rings of equal area x 8 sectors over r < 1.8.
    constexpr int kRings = 6, kSectors = 8;
    auto histogram = [&] {
        std::vector<double> bins(kRings * kSectors, 0.0);
        for (const Vec3& p : spots.positions()) {
            const double r = std::hypot(p.x, p.y);
            if (!(r < 1.8)) continue;
            const int ring = std::min(static_cast<int>(kRings * (r * r) / (1.8 * 1.8)), kRings - 1);
            const double angle = std::atan2(p.y, p.x) + kPi;
            const int sector =
                std::min(static_cast<int>(angle / (2 * kPi) * kSectors), kSectors - 1);
            bins[ring * kSectors + sector] += 1;
        }
        return bins;
    };
    auto chi_square = [](const std::vector<double>& bins, double& ratio, double& total) {
        total = 0;
        for (double b : bins) total += b;
        const double expected = total / bins.size();
        double chi = 0;
        for (double b : bins) chi += (b - expected) * (b - expected) / expected;
        const auto [lo, hi] = std::minmax_element(bins.begin(), bins.end());
        ratio = *hi / std::max(*lo, 1.0);
        return chi;
    };
    double ratio0 = 0, total0 = 0;
    const double chi0 = chi_square(histogram(), ratio0, total0);
    double worst_chi = chi0, worst_ratio = ratio0, lo_total = total0, hi_total = total0;
    for (int k = 1; k <= 120; ++k) {
        spots.advance();
        for (const Vec3& p : spots.positions()) ASSERT_LT(std::abs(p.z), 0.25);
        if (k % 20 != 0) continue;
        double ratio = 0, total = 0;
        const auto bins_k = histogram();
        const double chi = chi_square(bins_k, ratio, total);
        std::printf("frame %d: chi-square %.1f (47 dof), max/min bin %.3f, %g spots in r < 1.8\n",
                    k, chi, ratio, total);
        worst_chi = std::max(worst_chi, chi);
        worst_ratio = std::max(worst_ratio, ratio);
        lo_total = std::min(lo_total, total);
        hi_total = std::max(hi_total, total);
    }
    std::printf(
        "frame 0: chi-square %.1f, max/min %.3f; worst chi %.1f, ratio %.3f; in disk "
        "%g..%g\n",
        chi0, ratio0, worst_chi, worst_ratio, lo_total, hi_total);
    // Measured (frames 20..120 every 20): chi-square 29.0 .. 39.1 over the 48 bins (frame 0's
    // uniform sample: 48.5; 47 degrees of freedom, so the spots are as even as a uniform
    // sample), max/min bin 1.26 .. 1.35 (frame 0: 1.354); bounds: chi-square 48.5 x 1.5 (the
    // chi-square's 99.9th percentile at 47 dof is 82.7), ratio 1.354 + 0.2.
    EXPECT_LT(worst_chi, 48.5 * 1.5);
    EXPECT_LT(worst_ratio, 1.354 + 0.2);
    // The disk's share of the spots: expected 20000 x pi 1.8^2 / 16 = 12723 (frame 0: 12633);
    // measured 12078 .. 12217 later, up to 5.1% low: the cubes straddling r = 2 are refilled over
    // their whole volume though only their corners lose spots, so the ring 1.8 < r < 2 gains
    // (3560 for 2985 at frame 120) and the disk gives up the difference. Bound: 7% either way.
    const double expected = 20000 * kPi * 1.8 * 1.8 / 16;
    EXPECT_GT(lo_total, expected * 0.93);
    EXPECT_LT(hi_total, expected * 1.07);
}

TEST(SpotNoise, EllipsesPointAlongTheProjectedVelocity) {
    const RotatingBand rotating;
    const SpotNoise spots = rotating.spots(0.05, 40);
    Camera c;
    c.parallel = true;
    c.parallel_scale = 2.0;
    c.position = Vec3(0, 0, 5);
    c.view_up = Vec3(0, 1, 0);
    const CameraFrame frame(c, 512, 512);  // 128 px per unit, x right, y up
    SpotRasterOptions r;
    r.sigma_px = 1.5;
    r.stretch = 1.0;
    r.dt = 0.04;  // at r = 1: 5 px a frame, sigma_long 6.6 px
    SpotBuffers buffers;
    splat_spots(View{.camera = &frame}, spots, r, buffers);
    double worst = 0;
    int checked = 0;
    for (std::size_t i = 0; i < spots.size(); ++i) {
        const auto e = spot_ellipse(frame, spots.positions()[i], spots.velocities()[i], r);
        ASSERT_TRUE(e);
        if (e->sigma_long < 2.0 * e->sigma_short) continue;  // too round to have an axis
        const double reach = 3.0 * e->sigma_long;
        bool isolated = e->centre.x > reach && e->centre.y > reach && e->centre.x < 512 - reach &&
                        e->centre.y < 512 - reach;
        for (std::size_t j = 0; j < spots.size() && isolated; ++j) {
            if (j == i) continue;
            const auto other = spot_ellipse(frame, spots.positions()[j], spots.velocities()[j], r);
            isolated =
                glm::length(other->centre - e->centre) > 3.0 * (e->sigma_long + other->sigma_long);
        }
        if (!isolated) continue;
        // Second moments of the coverage around the centre.
        double m = 0, mx = 0, my = 0, mxx = 0, myy = 0, mxy = 0;
        for (int y = static_cast<int>(e->centre.y - reach); y <= e->centre.y + reach; ++y) {
            for (int x = static_cast<int>(e->centre.x - reach); x <= e->centre.x + reach; ++x) {
                const double w = buffers.coverage[static_cast<std::size_t>(y) * 512 + x];
                const double dx = x + 0.5 - e->centre.x, dy = y + 0.5 - e->centre.y;
                m += w;
                mx += w * dx;
                my += w * dy;
                mxx += w * dx * dx;
                myy += w * dy * dy;
                mxy += w * dx * dy;
            }
        }
        mx /= m;
        my /= m;
        const double cxx = mxx / m - mx * mx, cyy = myy / m - my * my, cxy = mxy / m - mx * my;
        const double axis = 0.5 * std::atan2(2 * cxy, cxx - cyy);
        // The projected velocity on the image: x right, y down (independent of spot_ellipse).
        const Vec3 vel = spots.velocities()[i];
        const double expected = std::atan2(-vel.y, vel.x);
        double diff = std::fmod(std::abs(axis - expected), kPi);
        diff = std::min(diff, kPi - diff);
        worst = std::max(worst, diff * 180 / kPi);
        ++checked;
    }
    std::printf("isolated elongated spots %d, largest axis error %.4f deg\n", checked, worst);
    // Measured: 9 spots, largest error 0.0304 deg (the 3-sigma cut and pixel sampling);
    // bound 0.1 deg, well inside the 2 deg the issue asks for.
    EXPECT_GE(checked, 5);
    EXPECT_LT(worst, 0.1);
}

TEST(SpotNoise, EachPixelsCoverageIsTheSumOfTheSpotsGaussians) {
    // Spots of every shape the raster has: round and small (sigma 1.5 px, drawn as products of
    // exponentials), stretched along the flow (up to sigma 6.6 px along, by rows), against the
    // sum over the spots of exp(-q / 2) where q < 9, in double from spot_ellipse.
    const RotatingBand rotating;
    const SpotNoise spots = rotating.spots(0.05, 300);
    Camera c;
    c.parallel = true;
    c.parallel_scale = 2.0;
    c.position = Vec3(0.3, 0.2, 5);
    c.focal_point = Vec3(0.3, 0.2, 0);
    c.view_up = Vec3(0, 1, 0);
    const CameraFrame frame(c, 256, 256);  // 64 px per unit
    for (double dt : {0.0, 0.04, 0.1}) {
        SCOPED_TRACE(dt);
        SpotRasterOptions r;
        r.dt = dt;  // 0: every spot round; 0.1 at r = 1: sigma_long 7.9 px
        SpotBuffers buffers;
        splat_spots(View{.camera = &frame}, spots, r, buffers);
        std::vector<double> expected(256 * 256, 0.0);
        std::vector<char> on_cut(256 * 256, 0);
        for (std::size_t i = 0; i < spots.size(); ++i) {
            const auto e = spot_ellipse(frame, spots.positions()[i], spots.velocities()[i], r);
            ASSERT_TRUE(e);
            const glm::dvec2 u = e->direction;
            for (int y = 0; y < 256; ++y) {
                for (int x = 0; x < 256; ++x) {
                    const glm::dvec2 d(x + 0.5 - e->centre.x, y + 0.5 - e->centre.y);
                    const double along = glm::dot(d, u) / e->sigma_long;
                    const double across = (d.x * -u.y + d.y * u.x) / e->sigma_short;
                    const double q = along * along + across * across;
                    const std::size_t p = static_cast<std::size_t>(y) * 256 + x;
                    if (q < 9.0) expected[p] += std::exp(-0.5 * q);
                    if (std::abs(q - 9.0) < 1e-3) on_cut[p] = 1;  // float and double may differ
                }
            }
        }
        double worst = 0, covered = 0;
        for (std::size_t p = 0; p < expected.size(); ++p) {
            if (on_cut[p]) continue;
            worst = std::max(worst, std::abs(buffers.coverage[p] - expected[p]));
            covered += expected[p] > 0;
        }
        std::printf("[ dt %.2f ] %.0f pixels covered; largest difference from the sum %.2e\n", dt,
                    covered, worst);
        EXPECT_GT(covered, 3000);
        // Measured 1.6e-7 (dt 0), 6.3e-7 (0.04), 2.8e-6 (0.1: sums of more overlapping spots):
        // float rounding of the sums.
        EXPECT_LT(worst, dt < 0.05 ? 1e-6 : 4e-6);
    }
}

TEST(SpotNoise, BadInputIsAOneLineError) {
    MeshFixture f = fixture(glm::dmat3(0.0), Vec3(1, 0, 0));
    ASSERT_TRUE(f.mesh.add_point_field(f.field).ok());  // a vector array of the mesh too
    const PointLocator locator(f.mesh, f.adjacency);
    const AnalyticFlow flow = uniform_flow(Vec3(1, 0, 0));
    SpotNoiseOptions o;
    o.band = 0.1;
    o.iso = 2.5;
    auto r = SpotNoise::create(f.mesh, locator, z_field(f), flow, o);
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.error().message.find("outside 'z''s range [-2, 2]"), std::string::npos)
        << r.error().message;
    o.iso = 0;
    o.count = 0;
    r = SpotNoise::create(f.mesh, locator, z_field(f), flow, o);
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.error().message.find("count must be 1 .."), std::string::npos);
    o.count = kMaxSpots + 1;
    EXPECT_FALSE(SpotNoise::create(f.mesh, locator, z_field(f), flow, o).ok());
    o.count = 10;
    r = SpotNoise::create(f.mesh, locator, f.field, flow, o);
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.error().message.find("not a scalar point array"), std::string::npos);
    EXPECT_TRUE(SpotNoise::create(f.mesh, locator, z_field(f), flow, o).ok());

    // Through spot_noise_frames: unknown and vector arrays name the scalar arrays.
    const VelocityField velocity = VelocityField::steady(f.mesh, f.field).value();
    SpotNoiseFramesOptions fo;
    fo.scalar = "nope";
    fo.spots.iso = 0;
    fo.spots.count = 10;
    auto none = [](int, const Image&) { return Status{}; };
    auto fr = spot_noise_frames(f.mesh, f.adjacency, velocity, fo, none);
    ASSERT_FALSE(fr.ok());
    EXPECT_EQ(fr.error().message, "no point array 'nope' (scalar arrays: z)");
    fo.scalar = "velocity";
    fr = spot_noise_frames(f.mesh, f.adjacency, velocity, fo, none);
    ASSERT_FALSE(fr.ok());
    EXPECT_NE(fr.error().message.find("has 3 components"), std::string::npos);
}

TEST(SpotNoise, ZeroVelocityGivesStillFrames) {
    const MeshFixture f = fixture(glm::dmat3(0.0), Vec3(0.0));
    const VelocityField velocity = VelocityField::steady(f.mesh, f.field).value();
    SpotNoiseFramesOptions fo;
    fo.scalar = "z";
    fo.spots.iso = 0.5;
    fo.spots.count = 2000;
    fo.steps = 5;
    fo.width = fo.height = 64;
    std::vector<Image> frames;
    const auto report =
        spot_noise_frames(f.mesh, f.adjacency, velocity, fo, [&](int, const Image& picture) {
            frames.push_back(picture);
            return Status{};
        });
    ASSERT_TRUE(report.ok()) << report.error().message;
    ASSERT_EQ(frames.size(), 6u);
    EXPECT_EQ(report->reseeded, 0u);
    double lit = 0;
    for (const Vec3f& p : frames[0].pixels) lit += p.x + p.y + p.z > 0;
    EXPECT_GT(lit, 64 * 64 / 10);  // the spots are drawn
    for (const Image& frame : frames) EXPECT_EQ(frame.pixels, frames[0].pixels);
}

TEST(SpotNoise, OpaqueGeometryInFrontHidesSpotsAndThreadsDoNotMatter) {
    const MeshFixture f = fixture(rotation_matrix(1.0), Vec3(0.0));
    const PointLocator locator(f.mesh, f.adjacency);
    const VelocityField velocity = VelocityField::steady(f.mesh, f.field).value();
    const MeshFlow flow(f.mesh, f.adjacency, velocity);
    SpotNoiseOptions o;
    o.iso = 0.0;
    o.band = 0.2;
    o.count = 3000;
    SpotNoise spots = SpotNoise::create(f.mesh, locator, z_field(f), flow, o).value();
    const CameraFrame frame(framing_camera(f.mesh.bounds(), Vec3(0.3, -1, 1)), 96, 96);
    SpotRasterOptions r;
    SpotBuffers open, hidden;
    View view{.camera = &frame};
    splat_spots(view, spots, r, open);
    // A surface at ray parameter 1 (the eye is farther than that from every spot) hides all.
    const std::vector<double> near(96 * 96, 1.0), far(96 * 96, 1e300);
    const Image grey(96, 96, Vec3f(0.5f));
    view.opaque_color = &grey;
    view.opaque_depth = &near;
    Image picture;
    render_spots(view, spots, r, hidden, picture);
    double covered = 0;
    for (float w : open.coverage) covered += w;
    EXPECT_GT(covered, 1000.0);
    for (float w : hidden.coverage) ASSERT_EQ(w, 0.0f);
    for (const Vec3f& p : picture.pixels) ASSERT_EQ(p, Vec3f(0.5f));
    view.opaque_depth = &far;
    splat_spots(view, spots, r, hidden);
    EXPECT_EQ(hidden.coverage, open.coverage);

    // Advection and raster are the same with one thread.
    spots.advance();
    splat_spots(view, spots, r, open);
    const std::vector<Vec3> positions(spots.positions().begin(), spots.positions().end());
    set_thread_count(1);
    SpotNoise serial = SpotNoise::create(f.mesh, locator, z_field(f), flow, o).value();
    serial.advance();
    SpotBuffers one;
    splat_spots(view, serial, r, one);
    set_thread_count(0);
    EXPECT_TRUE(std::equal(positions.begin(), positions.end(), serial.positions().begin()));
    EXPECT_EQ(one.coverage, open.coverage);
    EXPECT_EQ(one.intensity, open.intensity);
}

}  // namespace
}  // namespace tr
