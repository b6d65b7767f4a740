// The pipeline: methods dispatched by name, a `volumes` scene of one entry rendering as the
// top-level keys, the exact-sort policy judged on the mesh actually sorted, what is kept
// between views, and flow volumes and opaque surfaces through the one entry point.
#include <core/config.h>
#include <mesh/tetrahedralize.h>
#include <pipeline/methods/method.h>
#include <pipeline/methods/splat_method.h>
#include <pipeline/pipeline.h>
#include <pipeline/quick_scene.h>
#include <project/colormap.h>
#include <project/opaque_geometry.h>
#include <sort/order_verifier.h>
#include <tests/support/image_check.h>
#include <tests/support/mixed_grid.h>
#include <tests/support/test_scenes.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

namespace tr {
namespace {

using testing::make_mixed_grid;
using testing::MixedGridOptions;

// A mixed grid over [0, n]^3 (minus `skip`'s boxes) with scalar "wave" and velocity "v".
std::shared_ptr<const TetMesh> grid(int n, bool (*skip)(int, int, int) = nullptr, int nz = 0) {
    MixedGridOptions o;
    o.nx = o.ny = n;
    o.nz = nz > 0 ? nz : n;
    o.skip_box = skip;
    auto mesh = tetrahedralize(make_mixed_grid(o)).value();
    std::vector<double> wave, v;
    for (const Vec3& p : mesh.points()) {
        wave.push_back(0.5 + 0.45 * std::sin(1.3 * p.x) * std::cos(0.9 * p.y + 0.4 * p.z));
        v.insert(v.end(), {1.0, 0.2 * std::sin(p.x), 0.0});
    }
    EXPECT_TRUE(mesh.add_point_field(make_double_field("wave", 1, wave)).ok());
    EXPECT_TRUE(mesh.add_point_field(make_double_field("v", 3, v)).ok());
    return std::make_shared<const TetMesh>(std::move(mesh));
}

MethodSpec method(const std::string& name, std::optional<int> repetitions = {},
                  std::optional<std::int64_t> seed = {}) {
    MethodSpec m;
    m.name = name;
    m.repetitions = repetitions;
    m.seed = seed;
    return m;
}

bool ring(int i, int j, int) { return i >= 1 && i <= 3 && j >= 1 && j <= 3; }

Scene scene_of(std::shared_ptr<const TetMesh> mesh, int size = 96) {
    Scene scene;
    SceneVolume v;
    v.mesh = "grid";
    v.tets = std::move(mesh);
    v.scalar = "wave";
    v.transfer_function = make_quick_transfer_function("viridis", 0.05, 0.95, 0.6, 1.5).value();
    scene.volumes.push_back(std::move(v));
    scene.camera = framing_camera(scene.volumes[0].tets->bounds(), kDefaultViewDirection);
    scene.width = scene.height = size;
    scene.background = Vec3(0.05, 0.05, 0.1);
    return scene;
}

bool identical(const Image& a, const Image& b) {
    return a.width == b.width && a.height == b.height &&
           std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(Vec3f)) == 0;
}

TEST(Methods, EveryNameOfTheSpecDispatches) {
    EXPECT_EQ(method_names(),
              (std::vector<std::string>{"projected-tetrahedra", "pbvr-object", "pbvr-image",
                                        "splat", "texture-advection", "spot-noise"}));
    for (const std::string& name : method_names()) {
        ASSERT_NE(find_method(name), nullptr) << name;
        EXPECT_EQ(find_method(name)->name(), name);
    }
    EXPECT_EQ(find_method("raytrace"), nullptr);
}

TEST(Methods, UnknownNameIsAnErrorListingTheMethods) {
    Scene scene = scene_of(grid(2));
    scene.source = "s.json";
    scene.method = method("raytrace");
    Pipeline pipeline;
    auto result = pipeline.render(scene);
    ASSERT_FALSE(result.ok());
    const std::string line = result.error().to_string();
    EXPECT_EQ(line.rfind("s.json: error: $.method.name: unknown method 'raytrace'", 0), 0u) << line;
    EXPECT_NE(line.find("projected-tetrahedra, pbvr-object, pbvr-image, splat"), std::string::npos)
        << line;
}

// Splatting through the pipeline: its keys checked before loading, what it does not draw
// refused, and the mesh's points splatted near the projected-tetrahedra picture of the same
// field (the kernel's reconstruction is not the tets' linear one: measured below).
TEST(Methods, SplatDrawsThePointsAndRefusesWhatItCannot) {
    // A lattice: the cube [0, 6]^3 in cells of 0.375, split into tets without new points.
    TetMesh lattice = testing::uniform_box(16, 6.0);
    std::vector<double> wave;
    for (const Vec3& p : lattice.points()) {
        wave.push_back(0.5 + 0.45 * std::sin(1.3 * p.x) * std::cos(0.9 * p.y + 0.4 * p.z));
    }
    ASSERT_TRUE(lattice.add_point_field(make_double_field("wave", 1, wave)).ok());
    Pipeline pipeline;
    Scene scene = scene_of(std::make_shared<const TetMesh>(std::move(lattice)), 64);
    const auto pt = pipeline.render(scene).value();
    scene.method = method("splat");
    auto splat = pipeline.render(scene);
    ASSERT_TRUE(splat.ok()) << splat.error().to_string();
    EXPECT_EQ(std::get<std::string>(*splat->stats.find("kernel")), "crawfis-max");
    EXPECT_NEAR(splat->stats.number("spacing"), 0.375, 1e-12);  // the lattice's
    const ImageComparison c = compare_images(splat->image, pt.image, Vec3f(scene.background));
    std::printf("[ splat vs projected tetrahedra ] %.2f dB, largest %.4f\n", c.psnr_foreground,
                c.max_difference);
    // Measured 25.2 dB, largest 0.30: at 64 x 64 the kernel's blur of the lattice's edges (1.5
    // cells past them) and of its 16-cell waves is what differs. Bounds 1.5 dB and a quarter.
    EXPECT_GT(c.psnr_foreground, 23.7);
    EXPECT_LT(c.max_difference, 0.38);
    scene.method->options["kernel"] = std::string("gaussian");
    scene.method->options["spacing"] = 1.5;
    auto gaussian = pipeline.render(scene);
    ASSERT_TRUE(gaussian.ok()) << gaussian.error().to_string();
    EXPECT_EQ(gaussian->stats.number("spacing"), 1.5);
    // Westover's sheet buffer: one sheet per lattice plane (17) across the axis nearest the
    // view, at the lattice's own spacing.
    scene.method->options.erase("spacing");
    scene.method->options["compositing"] = std::string("sheet-buffer");
    auto sheets = pipeline.render(scene);
    ASSERT_TRUE(sheets.ok()) << sheets.error().to_string();
    EXPECT_EQ(std::get<std::string>(*sheets->stats.find("compositing")), "sheet-buffer");
    EXPECT_EQ(sheets->stats.number("spacing"), 0.375);
    EXPECT_EQ(sheets->stats.number("sheets"), 17);
    // Bad keys, before anything is loaded.
    auto error_of = [&](Scene bad) {
        auto r = Pipeline().render(bad);
        return r.ok() ? std::string() : r.error().to_string();
    };
    Scene bad = scene;
    bad.method->options["kernel"] = std::string("box");
    EXPECT_NE(error_of(bad).find("$.method.kernel: expected"), std::string::npos);
    bad = scene;
    bad.method->options["spacing"] = -1.0;
    EXPECT_NE(error_of(bad).find("$.method.spacing: expected a number > 0"), std::string::npos);
    bad = scene;
    bad.method->options["compositing"] = std::string("sheets");
    EXPECT_NE(error_of(bad).find("$.method.compositing: expected \"per-splat\" or "
                                 "\"sheet-buffer\""),
              std::string::npos);
    bad = scene;
    bad.method->options["depth"] = std::string("entry");
    EXPECT_NE(error_of(bad).find("unknown key for splat"), std::string::npos);
    bad = scene;
    bad.volumes.push_back(bad.volumes[0]);
    bad.volumes_key = true;
    EXPECT_NE(error_of(bad).find("splat: draws one volume"), std::string::npos);
}

// Textured vector splats through the pipeline: render_splat_cycle gives N frames, frame k of
// the cycle is the scene rendered with key frame = k (and k + N), the frames differ; a vector
// array that is a scalar, a missing one, and keys that need vectors are refused in one line.
TEST(Methods, SplatVectorCycleAndItsRefusals) {
    TetMesh lattice = testing::uniform_box(8, 4.0);
    std::vector<double> wave, swirl;
    for (const Vec3& p : lattice.points()) {
        wave.push_back(0.5 + 0.4 * std::sin(1.3 * p.x));
        swirl.insert(swirl.end(), {-(p.y - 2), p.x - 2, 0.2});
    }
    ASSERT_TRUE(lattice.add_point_field(make_double_field("wave", 1, wave)).ok());
    ASSERT_TRUE(lattice.add_point_field(make_double_field("swirl", 3, swirl)).ok());
    Pipeline pipeline;
    Scene scene = scene_of(std::make_shared<const TetMesh>(std::move(lattice)), 64);
    auto cycle = render_splat_cycle(pipeline, scene, "swirl", 4);
    ASSERT_TRUE(cycle.ok()) << cycle.error().to_string();
    ASSERT_EQ(cycle->frames.size(), 4u);
    EXPECT_GT(cycle->stats.number("splats_drawn"), 650);  // measured 729; bound a tenth below
    scene.method = method("splat");
    scene.method->options["vectors"] = std::string("swirl");
    scene.method->options["cycle"] = std::int64_t{4};
    for (std::int64_t k : {1, 5, -3}) {
        scene.method->options["frame"] = k;
        auto one = pipeline.render(scene);
        ASSERT_TRUE(one.ok()) << one.error().to_string();
        EXPECT_EQ(compare_images(one->image, cycle->frames[1], Vec3f(0.0f)).max_difference, 0.0);
    }
    // Measured 0.321 between frames 0 and 1; a quarter below.
    const double change =
        compare_images(cycle->frames[0], cycle->frames[1], Vec3f(0.0f)).max_difference;
    std::printf("[ vector splat cycle ] frames 0 and 1 differ by %.3f at most\n", change);
    EXPECT_GT(change, 0.24);
    auto error_of = [&](Scene bad) {
        auto r = Pipeline().render(bad);
        return r.ok() ? std::string() : r.error().to_string();
    };
    Scene bad = scene;
    bad.method->options["vectors"] = std::string("wave");
    EXPECT_NE(error_of(bad).find(
                  "splat: the point array 'wave' has 1 component (a scalar); vectors need 3"),
              std::string::npos)
        << error_of(bad);
    bad.method->options["vectors"] = std::string("nothing");
    EXPECT_NE(error_of(bad).find("splat: no point array 'nothing' for the vectors"),
              std::string::npos);
    bad = scene;
    bad.method->options["compositing"] = std::string("sheet-buffer");
    EXPECT_NE(error_of(bad).find("$.method.compositing: the sheet buffer is for scalar splats"),
              std::string::npos);
    bad = scene;
    bad.method->options.erase("vectors");
    EXPECT_NE(error_of(bad).find("$.method.cycle: applies to vector splats"), std::string::npos);
    bad = scene;
    bad.method->options["cycle"] = std::int64_t{0};
    EXPECT_NE(error_of(bad).find("$.method.cycle: expected an integer from 1 to 1024"),
              std::string::npos);
    EXPECT_FALSE(render_splat_cycle(pipeline, scene, "swirl", 0).ok());
    auto scalar_cycle = render_splat_cycle(pipeline, scene, "wave", 4);
    ASSERT_FALSE(scalar_cycle.ok());
    EXPECT_NE(scalar_cycle.error().to_string().find("has 1 component (a scalar)"),
              std::string::npos);
}

TEST(Methods, ProjectedTetrahedraRejectKeysOfOtherMethodsAndNoteRepetitions) {
    const std::shared_ptr<const TetMesh> mesh = grid(3);
    Scene scene = scene_of(mesh);
    MethodSpec with_depth = method("projected-tetrahedra");
    with_depth.options["depth"] = std::string("entry");
    scene.method = with_depth;
    Pipeline pipeline;
    auto rejected = pipeline.render(scene);
    ASSERT_FALSE(rejected.ok());
    EXPECT_NE(rejected.error().message.find("$.method.depth: unknown key for projected-tetrahedra"),
              std::string::npos)
        << rejected.error().message;
    // repetitions and seed are the stochastic methods': noted, and the picture is unchanged.
    scene.method = method("projected-tetrahedra", 64, 3);
    auto noted = pipeline.render(scene);
    ASSERT_TRUE(noted.ok()) << noted.error().to_string();
    ASSERT_EQ(noted->notes.size(), 1u);
    EXPECT_NE(noted->notes[0].find("ignore"), std::string::npos);
    scene.method.reset();
    auto plain = pipeline.render(scene);
    ASSERT_TRUE(plain.ok());
    EXPECT_TRUE(plain->notes.empty());
    EXPECT_TRUE(identical(noted->image, plain->image));
}

TEST(Volumes, OneEntryRendersExactlyAsTheTopLevelKeys) {
    const std::shared_ptr<const TetMesh> mesh = grid(3);
    Scene top = scene_of(mesh);
    Scene listed = top;
    listed.volumes_key = true;
    Pipeline a, b;
    auto one = a.render(top);
    auto other = b.render(listed);
    ASSERT_TRUE(one.ok() && other.ok());
    EXPECT_TRUE(identical(one->image, other->image));
    const std::size_t covered = compare_images(one->image, Image(96, 96, Vec3f(0.05f, 0.05f, 0.1f)),
                                               Vec3f(0.05f, 0.05f, 0.1f))
                                    .foreground_pixels;
    // The volume covers the middle of the picture: measured 4,912 of 9,216 pixels; bound 4,400
    // (a tenth below).
    EXPECT_GT(covered, 4400u);
}

TEST(Volumes, SeveralAreMergedPerPixel) {
    Scene scene = scene_of(grid(2));
    scene.volumes.push_back(scene.volumes[0]);  // the same medium twice: twice the extinction
    scene.volumes_key = true;
    Pipeline pipeline;
    auto twice = pipeline.render(scene);
    ASSERT_TRUE(twice.ok()) << twice.error().to_string();
    EXPECT_EQ(std::get<std::string>(*twice->stats.find("compositing")), "merged");
    EXPECT_EQ(twice->stats.number("volumes"), 2.0);
    // Measured 26,427 overlapping intervals; bound 23,700 (a tenth below).
    EXPECT_GT(twice->stats.number("overlap_intervals"), 23700.0);
    scene.volumes.pop_back();
    auto once = pipeline.render(scene);
    ASSERT_TRUE(once.ok());
    EXPECT_EQ(std::get<std::string>(*once->stats.find("compositing")), "sorted");
    // Denser: further from the background wherever the volume shows.
    const Vec3f background(scene.background);
    double more = 0, less = 0;
    for (std::size_t p = 0; p < once->image.pixels.size(); ++p) {
        const double d1 = glm::length(once->image.pixels[p] - background);
        const double d2 = glm::length(twice->image.pixels[p] - background);
        (d2 >= d1 ? more : less) += d2 - d1;
    }
    // Measured: 646.5 summed over the pixels farther, 0 over those nearer (none is); bounds a
    // tenth below the one, float rounding for the other.
    EXPECT_GT(more, 580.0);
    EXPECT_GT(less, -1e-4);
    // A flow volume grows through one mesh only.
    Scene flow = scene_of(grid(2));
    flow.volumes.push_back(flow.volumes[0]);
    flow.flow_volume = FlowVolumeSpec{};
    EXPECT_FALSE(pipeline.render(flow).ok());
}

// A volume the camera cannot see draws nothing, and the result says so, naming it; one in view
// (the camera even inside it) gets no such note; for every method.
TEST(Volumes, OneOutOfViewIsNoted) {
    const auto out_of_view_notes = [](const RenderResult& r) {
        return std::count_if(r.notes.begin(), r.notes.end(), [](const std::string& n) {
            return n.find("no cell is in view") != std::string::npos;
        });
    };
    for (const char* name : {"projected-tetrahedra", "pbvr-image", "pbvr-object"}) {
        SCOPED_TRACE(name);
        Scene scene = scene_of(grid(2), 48);
        scene.method = method(name, 2);
        SceneVolume away = scene.volumes[0];
        away.mesh = "far";
        std::vector<Vec3> points = away.tets->points();
        for (Vec3& p : points) p.z -= 1000;  // far below the view
        TetMesh far = TetMesh::create(points, away.tets->tets()).value();
        for (const Field& f : away.tets->point_fields()) ASSERT_TRUE(far.add_point_field(f).ok());
        away.tets = std::make_shared<const TetMesh>(std::move(far));
        scene.volumes.push_back(away);
        scene.volumes_key = true;
        Pipeline pipeline;
        auto both = pipeline.render(scene);
        ASSERT_TRUE(both.ok()) << both.error().to_string();
        EXPECT_EQ(out_of_view_notes(*both), 1);
        bool named = false;
        for (const std::string& n : both->notes) named |= n.find("volume 1 (far)") == 0;
        EXPECT_TRUE(named);
        // The visible one alone: no note; its picture is the one drawn with the other.
        scene.volumes.pop_back();
        auto one = pipeline.render(scene);
        ASSERT_TRUE(one.ok());
        EXPECT_EQ(out_of_view_notes(*one), 0);
        // Seen from inside the volume, near a corner: in view. pbvr-object refuses it (its
        // density grows as 1 / depth^2 towards the eye: the work would have no bound) with
        // an error that says why, instead of running for hours.
        scene.camera.position = scene.volumes[0].tets->bounds().lo + Vec3(0.1);
        auto inside = pipeline.render(scene);
        if (std::string(name) == "pbvr-object") {
            ASSERT_FALSE(inside.ok());
            EXPECT_NE(inside.error().message.find("inside or very near"), std::string::npos)
                << inside.error().to_string();
        } else {
            ASSERT_TRUE(inside.ok()) << inside.error().to_string();
            EXPECT_EQ(out_of_view_notes(*inside), 0);
        }
    }
}

// Counts wrong-way pairs of an order over `views` random views.
std::size_t violations(Pipeline& pipeline, const SceneVolume& volume, SortMethod method,
                       int views) {
    std::size_t total = 0;
    const auto mesh = pipeline.mesh(volume).value();
    for (int v = 0; v < views; ++v) {
        const CameraFrame frame(random_view(mesh->tets.bounds(), 100 + v, false, false), 96, 96);
        const ViewOrder order = pipeline.visibility_order(volume, frame, method).value();
        total += check_order(order.prepared.mesh(), order.order, frame).violations;
    }
    return total;
}

TEST(ExactSortPolicy, JudgedOnTheMeshActuallySorted) {
    Pipeline pipeline;
    // A ring of boxes: non-convex, with a hole.
    Scene ring_scene = scene_of(grid(5, ring, 2));
    const SceneVolume& volume = ring_scene.volumes[0];
    const PreparedSort bare = pipeline.prepared_sort(volume, SortMethod::kMpvo).value();
    EXPECT_FALSE(bare.sorted->real_convex);
    EXPECT_FALSE(bare.sorted->convexified);
    EXPECT_FALSE(bare.exact);  // MPVO on a non-convex mesh claims nothing
    EXPECT_GT(violations(pipeline, volume, SortMethod::kMpvo, 8), 0u);  // and is wrong
    for (SortMethod m : {SortMethod::kMpvoNonConvex, SortMethod::kCentroid}) {
        EXPECT_FALSE(pipeline.prepared_sort(volume, m).value().exact);
    }
    for (SortMethod m : {SortMethod::kAuto, SortMethod::kExact}) {
        const PreparedSort p = pipeline.prepared_sort(volume, m).value();
#if TETRENDER_HAS_TETGEN
        EXPECT_TRUE(p.sorted->convexified);
        EXPECT_TRUE(p.sorted->sorted_convex);  // checked on real + virtual tets
        EXPECT_TRUE(p.exact);
        EXPECT_TRUE(p.note.empty());
        EXPECT_EQ(violations(pipeline, volume, m, 8), 0u);
#else
        EXPECT_FALSE(p.exact);
        EXPECT_NE(p.note.find("not exact"), std::string::npos);
#endif
    }
    // A convex box: exact without any fill, and the bare and filled preparations are one.
    Scene box_scene = scene_of(grid(3));
    const PreparedSort box =
        pipeline.prepared_sort(box_scene.volumes[0], SortMethod::kAuto).value();
    EXPECT_TRUE(box.sorted->real_convex);
    EXPECT_FALSE(box.sorted->convexified);
    EXPECT_TRUE(box.exact);
    EXPECT_EQ(box.sorted.get(),
              pipeline.prepared_sort(box_scene.volumes[0], SortMethod::kMpvo).value().sorted.get());
    // claims_exactness itself follows the sorted mesh, for every MPVO-family name.
    for (SortMethod m : {SortMethod::kAuto, SortMethod::kExact, SortMethod::kMpvo}) {
        EXPECT_FALSE(claims_exactness(m, false)) << sort_method_name(m);
        EXPECT_TRUE(claims_exactness(m, true)) << sort_method_name(m);
    }
    EXPECT_FALSE(claims_exactness(SortMethod::kCentroid, true));
}

TEST(Pipeline, KeepsWhatItLoadedAndPreparedBetweenViews) {
    const std::shared_ptr<const TetMesh> mesh = grid(5, ring, 2);
    Scene scene = scene_of(mesh);
    Pipeline pipeline;
    auto first = pipeline.render(scene);
    ASSERT_TRUE(first.ok()) << first.error().to_string();
    const LoadedMesh* loaded = pipeline.mesh(scene.volumes[0]).value().get();
    const SortedMesh* sorted =
        pipeline.prepared_sort(scene.volumes[0], SortMethod::kAuto).value().sorted.get();
    // An orbit: another camera, the same pipeline.
    scene.camera = framing_camera(mesh->bounds(), Vec3(-0.3, 1.0, 0.5));
    auto second = pipeline.render(scene);
    ASSERT_TRUE(second.ok());
    EXPECT_EQ(pipeline.mesh(scene.volumes[0]).value().get(), loaded);
    EXPECT_EQ(pipeline.prepared_sort(scene.volumes[0], SortMethod::kAuto).value().sorted.get(),
              sorted);
    // The same picture as a pipeline that starts afresh for that view.
    Pipeline fresh;
    auto again = fresh.render(scene);
    ASSERT_TRUE(again.ok());
    EXPECT_TRUE(identical(second->image, again->image));
    EXPECT_FALSE(identical(first->image, second->image));
}

TEST(Pipeline, ErrorsOfTheScalarNameThePoint) {
    auto mesh = std::make_shared<TetMesh>(*grid(2));
    std::vector<double> bad(mesh->num_points(), 0.5);
    bad[7] = std::nan("");
    ASSERT_TRUE(mesh->add_point_field(make_double_field("bad", 1, bad)).ok());
    Scene scene = scene_of(mesh);
    scene.volumes[0].scalar = "bad";
    Pipeline pipeline;
    auto result = pipeline.render(scene);
    ASSERT_FALSE(result.ok());
    EXPECT_NE(result.error().message.find("not finite at point 7"), std::string::npos);
    scene.volumes[0].scalar = "missing";
    result = pipeline.render(scene);
    ASSERT_FALSE(result.ok());
    EXPECT_NE(result.error().message.find("wave"), std::string::npos)  // lists the arrays
        << result.error().message;
}

TEST(Pipeline, OpaqueSurfacesHandedOverOrFromTheMesh) {
    const std::shared_ptr<const TetMesh> mesh = grid(3);
    Scene scene = scene_of(mesh);
    OpaqueSpec body;
    body.color = Vec3(0.9, 0.1, 0.1);
    body.surface = std::make_shared<const SurfaceMesh>([&] {
        SurfaceMesh s = make_cylinder_surface(0.6, 0.5, 2.5, 24);
        for (Vec3& p : s.points) p += Vec3(1.5, 1.5, 0.0);
        return s;
    }());
    scene.opaque.push_back(body);
    Pipeline pipeline;
    auto with = pipeline.render(scene);
    ASSERT_TRUE(with.ok()) << with.error().to_string();
    Scene plain = scene_of(mesh);
    auto without = pipeline.render(plain);
    ASSERT_TRUE(without.ok());
    const ImageComparison c =
        compare_images(with->image, without->image, Vec3f(0.05f, 0.05f, 0.1f));
    // The red body shows through the volume: measured largest difference 0.549; bound 0.49 (a
    // tenth below).
    EXPECT_GT(c.max_difference, 0.49);
    OpaqueSpec side_set;
    side_set.side_set = "wall";
    plain.opaque.push_back(side_set);
    auto missing = pipeline.render(plain);
    ASSERT_FALSE(missing.ok());
    EXPECT_NE(missing.error().message.find("no side set 'wall'"), std::string::npos);
}

TEST(Pipeline, FlowVolumeLayerByLayer) {
    const std::shared_ptr<const TetMesh> mesh = grid(4);
    Scene scene = scene_of(mesh, 80);
    FlowVolumeSpec dye;
    dye.vectors = "v";
    dye.seed_center = Vec3(0.5, 2.0, 2.0);
    dye.seed_width = dye.seed_height = 1.0;
    dye.seed_resolution = 4;
    dye.steps = 5;
    dye.dt = 0.3;
    scene.flow_volume = dye;
    std::vector<std::size_t> layers;
    RenderOptions options;
    options.on_flow_volume_layer = [&](std::size_t layer, const Image& picture) {
        layers.push_back(layer);
        EXPECT_EQ(picture.width, 80);
        return Status{};
    };
    Pipeline pipeline;
    auto result = pipeline.render(scene, options);
    ASSERT_TRUE(result.ok()) << result.error().to_string();
    EXPECT_EQ(layers, (std::vector<std::size_t>{0, 1, 2, 3, 4}));
    ASSERT_NE(result->flow_volume, nullptr);
    EXPECT_EQ(result->flow_volume->layer_tets.size(), 5u);
    const std::size_t dyed = compare_images(result->image, Image(80, 80, Vec3f(0.05f, 0.05f, 0.1f)),
                                            Vec3f(0.05f, 0.05f, 0.1f))
                                 .foreground_pixels;
    EXPECT_GT(dyed, 245u);  // measured 274 pixels of dye; bound a tenth below
    // The reference ray caster draws no flow volume: an error, not another picture.
    options.reference = true;
    EXPECT_FALSE(pipeline.render(scene, options).ok());
}

}  // namespace
}  // namespace tr

namespace tr {
namespace {

// The most any channel of `over` differs from `transparent + (1 - alpha) behind`.
double largest_composite_error(const RenderResult& transparent, const RenderResult& over,
                               const Image& behind) {
    double worst = 0;
    for (std::size_t i = 0; i < over.image.pixels.size(); ++i) {
        const Vec3f expected =
            transparent.image.pixels[i] + (1.0f - transparent.alpha[i]) * behind.pixels[i];
        for (int c = 0; c < 3; ++c) {
            worst = std::max(worst,
                             static_cast<double>(std::abs(expected[c] - over.image.pixels[i][c])));
        }
    }
    return worst;
}

// A transparent render is the volume alone: put over the background (or the opaque surfaces'
// picture) it is the ordinary render, for each method that draws it; a method that cannot is
// refused before anything is loaded.
TEST(TransparentRender, OverTheBackgroundItIsTheOrdinaryPicture) {
    Scene scene = scene_of(grid(4, ring));
    // An opaque plate through the middle of the grid, half the volume in front of it.
    auto plate = std::make_shared<SurfaceMesh>();
    plate->points = {Vec3(-1, -1, 2.1), Vec3(5, -1, 2.1), Vec3(5, 5, 2.1), Vec3(-1, 5, 2.1)};
    plate->triangles = {{0, 1, 2}, {0, 2, 3}};
    // Projected tetrahedra twice: one volume (sorted) and two (merged per pixel).
    for (const std::string name :
         {"projected-tetrahedra", "projected-tetrahedra+", "pbvr-image", "pbvr-object"}) {
        for (const bool with_plate : {false, true}) {
            SCOPED_TRACE(name + (with_plate ? " over a plate" : ""));
            Scene s = scene;
            if (name.back() == '+') {
                s.volumes.push_back(s.volumes[0]);
                s.volumes[1].transfer_function =
                    make_quick_transfer_function("inferno", 0.05, 0.95, 0.3, 1.5).value();
                s.method = method("projected-tetrahedra");
            } else {
                s.method = method(name, 8, 5);
            }
            if (with_plate) {
                OpaqueSpec spec;
                spec.surface = plate;
                spec.color = Vec3(0.7, 0.3, 0.2);
                s.opaque.push_back(spec);
            }
            Pipeline pipeline;
            auto over = pipeline.render(s);
            ASSERT_TRUE(over.ok()) << over.error().to_string();
            RenderOptions options;
            options.transparent = true;
            auto alone = pipeline.render(s, options);
            ASSERT_TRUE(alone.ok()) << alone.error().to_string();
            ASSERT_EQ(alone->alpha.size(), over->image.pixels.size());
            Image behind(s.width, s.height, Vec3f(s.background));
            if (with_plate) {
                const CameraFrame frame(s.camera, s.width, s.height);
                behind = render_opaque(pipeline.opaque(s)->layers(), frame, s.background).color;
            }
            const double error = largest_composite_error(*alone, *over, behind);
            std::printf("[ transparent %s%s ] largest difference %.3g\n", name.c_str(),
                        with_plate ? " over a plate" : "", error);
            // Measured: at most 1.5e-7 (float rounding of the over operators).
            EXPECT_LE(error, 1e-6);
            EXPECT_GT(*std::max_element(alone->alpha.begin(), alone->alpha.end()), 0.5f);
        }
    }
    Scene splat = scene;
    splat.method = method("splat");
    RenderOptions options;
    options.transparent = true;
    const Status refused = Pipeline().check(splat, options);
    ASSERT_FALSE(refused.ok());
    EXPECT_NE(refused.error().message.find("transparent"), std::string::npos);
}

}  // namespace
}  // namespace tr
