// libFuzzer target: garbage mesh -> TetMesh -> face adjacency -> visibility sort -> render.
// The bytes are read (FuzzedDataProvider) as points (coordinates from a small grid, so that
// points coincide and tets are flat, or any double: NaN, inf, huge, subnormal), cells (ids
// mostly below the point count, one past it, or any 32-bit value) and a transfer function and
// scalars. The first byte picks the create path (TetMesh::create on tets, or
// make_unstructured_mesh + tetrahedralize on mixed cells of any VTK type id), the sort method,
// the integrator and the camera. A mesh that is accepted must hold: every id below the point
// count, every used point finite, every tet positively oriented (tet_mesh.h); an adjacency
// that is built, symmetric; each sort (and the pairwise exact order), a permutation of the real
// tets; a 16 x 16 render, finite pixels in [0, 1] over a background in [0, 1].

#include <core/camera.h>
#include <core/image.h>
#include <core/parallel.h>
#include <mesh/face_adjacency.h>
#include <mesh/tet_mesh.h>
#include <mesh/tetrahedralize.h>
#include <mesh/unstructured_mesh.h>
#include <project/cpu_renderer.h>
#include <project/segment_shader.h>
#include <project/transfer_function.h>
#include <sort/order_verifier.h>
#include <sort/visibility_sort.h>

#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <fuzzer/FuzzedDataProvider.h>
#include <limits>
#include <memory>
#include <vector>

namespace {

using namespace tr;

// A coordinate or scalar: mostly small grid values (coincident points, flat tets), some in
// a wider range, some any bit pattern, some special values.
double fuzz_double(FuzzedDataProvider& in) {
    const auto selector = in.ConsumeIntegral<std::uint8_t>();
    if (selector < 150) return static_cast<double>(selector % 9) - 4.0;
    if (selector < 200) return in.ConsumeIntegral<std::int16_t>() / 64.0;
    if (selector < 235) return std::bit_cast<double>(in.ConsumeIntegral<std::uint64_t>());
    constexpr double inf = std::numeric_limits<double>::infinity();
    static constexpr std::array<double, 12> specials = {
        std::numeric_limits<double>::quiet_NaN(),  inf,  -inf,  1e308,  -1e308, 1e-308,
        std::numeric_limits<double>::denorm_min(), -0.0, 1e154, 1e-154, 3e38,   1e-300};
    return specials[selector % specials.size()];
}

// A point id: mostly valid, sometimes one past the end, sometimes anything.
std::uint32_t fuzz_id(FuzzedDataProvider& in, std::size_t num_points) {
    const auto selector = in.ConsumeIntegral<std::uint8_t>();
    if (selector < 240)
        return in.ConsumeIntegralInRange<std::uint32_t>(0, static_cast<std::uint32_t>(num_points));
    return in.ConsumeIntegral<std::uint32_t>();
}

// A broken property: says which, then traps (a libFuzzer finding).
[[noreturn]] void finding(const char* what) {
    std::fprintf(stderr, "fuzz_mesh_pipeline: %s\n", what);
    __builtin_trap();
}

bool finite(const Vec3& p) {
    return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
}

void check_mesh(const TetMesh& mesh) {
    if (mesh.num_real_tets() != mesh.num_tets() || mesh.source_cells().size() != mesh.num_tets())
        finding("a created mesh has virtual tets or source cells not one per tet");
    for (const Tet& tet : mesh.tets()) {
        for (PointId p : tet) {
            if (p >= mesh.num_points() || !finite(mesh.point(p)))
                finding("a tet uses a point out of range or not finite");
        }
        const auto& pts = mesh.points();
        const double six_volume = orient3d(pts[tet[0]], pts[tet[1]], pts[tet[2]], pts[tet[3]]);
        if (!(six_volume > 0)) {
            for (PointId p : tet)
                std::fprintf(stderr, "  %a %a %a\n", pts[p].x, pts[p].y, pts[p].z);
            std::fprintf(stderr, "  orient3d %a\n", six_volume);
            finding("a tet is not positively oriented");
        }
    }
}

void check_adjacency(const TetMesh& mesh, const FaceAdjacency& adjacency) {
    if (adjacency.neighbors.size() != mesh.num_tets()) finding("adjacency size");
    for (std::size_t t = 0; t < adjacency.neighbors.size(); ++t) {
        for (CellId nb : adjacency.neighbors[t]) {
            if (nb == kNoCell) continue;
            if (nb >= mesh.num_tets() || nb == t)
                finding("a neighbour out of range or the tet itself");
            bool back = false;
            for (CellId other : adjacency.neighbors[nb]) back = back || other == t;
            if (!back) finding("adjacency not symmetric");
        }
    }
}

void check_permutation(const TetMesh& mesh, const std::vector<CellId>& order) {
    if (order.size() != mesh.num_real_tets()) finding("the order's size is not the real tet count");
    std::vector<bool> seen(mesh.num_real_tets(), false);
    for (CellId c : order) {
        if (c >= mesh.num_real_tets() || seen[c])
            finding("the order repeats a cell or names a cell out of range");
        seen[c] = true;
    }
}

std::shared_ptr<const TransferFunction> default_tf() {
    static const std::shared_ptr<const TransferFunction> tf =
        std::make_shared<const TransferFunction>(
            TransferFunction::create({{-4, Vec3(0, 0, 1)}, {0, Vec3(0, 1, 0)}, {4, Vec3(1, 0, 0)}},
                                     {{-4, 0.0}, {0, 0.5}, {4, 0.9}}, 1.0)
                .value());
    return tf;
}

// The transfer function from the bytes (control points anywhere, unit distance anything), or
// the default one when the bytes do not make a valid one.
std::shared_ptr<const TransferFunction> fuzz_tf(FuzzedDataProvider& in) {
    const std::size_t n = in.ConsumeIntegralInRange<std::size_t>(0, 4);
    if (n == 0) return default_tf();
    std::vector<ColorPoint> color;
    std::vector<OpacityPoint> opacity;
    double s = fuzz_double(in);
    for (std::size_t k = 0; k < n; ++k) {
        color.push_back({s, Vec3(in.ConsumeProbability<double>(), in.ConsumeProbability<double>(),
                                 in.ConsumeProbability<double>())});
        opacity.push_back({s, in.ConsumeProbability<double>() * 0.999999});
        s += std::abs(fuzz_double(in));
    }
    auto tf =
        TransferFunction::create(std::move(color), std::move(opacity), std::abs(fuzz_double(in)));
    if (!tf.ok()) return default_tf();
    return std::make_shared<const TransferFunction>(std::move(tf.value()));
}

Result<TetMesh> fuzz_mesh(FuzzedDataProvider& in, bool via_unstructured) {
    const std::size_t num_points = in.ConsumeIntegralInRange<std::size_t>(0, 40);
    std::vector<Vec3> points(num_points);
    for (Vec3& p : points) p = Vec3(fuzz_double(in), fuzz_double(in), fuzz_double(in));
    if (!via_unstructured) {
        const std::size_t num_tets = in.ConsumeIntegralInRange<std::size_t>(0, 48);
        std::vector<Tet> tets(num_tets);
        for (Tet& tet : tets) {
            for (PointId& p : tet) p = fuzz_id(in, num_points);
        }
        TetMeshCreateOptions options;
        // A non-negative finite tolerance (the option's domain; no file or flag sets it).
        if (in.ConsumeBool()) {
            const double tolerance = std::abs(fuzz_double(in));
            if (std::isfinite(tolerance)) options.degenerate_tolerance = tolerance;
        }
        return TetMesh::create(std::move(points), std::move(tets), {}, options);
    }
    static constexpr std::array<std::uint8_t, 14> kTypes = {10, 12, 13, 14, 11, 24, 25,
                                                            26, 27, 15, 16, 5,  9,  42};
    const std::size_t num_cells = in.ConsumeIntegralInRange<std::size_t>(0, 16);
    std::vector<std::uint8_t> types;
    std::vector<std::int64_t> connectivity, offsets;
    const bool explicit_offsets = in.ConsumeBool();
    offsets.push_back(0);
    for (std::size_t c = 0; c < num_cells; ++c) {
        const auto selector = in.ConsumeIntegral<std::uint8_t>();
        const std::uint8_t type =
            selector < 240 ? kTypes[selector % kTypes.size()] : in.ConsumeIntegral<std::uint8_t>();
        types.push_back(type);
        int nodes = cell_node_count(static_cast<CellType>(type));
        if (explicit_offsets && in.ConsumeIntegralInRange<int>(0, 15) == 0)
            nodes = in.ConsumeIntegralInRange<int>(0, 30);
        for (int k = 0; k < nodes; ++k) {
            connectivity.push_back(in.ConsumeIntegralInRange<int>(0, 31) == 0
                                       ? in.ConsumeIntegral<std::int64_t>()
                                       : static_cast<std::int64_t>(fuzz_id(in, num_points)));
        }
        offsets.push_back(static_cast<std::int64_t>(connectivity.size()));
    }
    if (!explicit_offsets) offsets.clear();
    std::vector<double> xyz;
    for (const Vec3& p : points) xyz.insert(xyz.end(), {p.x, p.y, p.z});
    auto unstructured = make_unstructured_mesh(xyz, connectivity, offsets, types);
    if (!unstructured.ok()) return unstructured.error();
    TetrahedralizeOptions options;
    options.merge_points = in.ConsumeBool();
    if (in.ConsumeBool()) options.merge_tolerance = std::abs(fuzz_double(in));
    options.skip_unsupported = in.ConsumeBool();
    TetrahedralizeReport report;
    auto mesh = tetrahedralize(unstructured.value(), options, &report);
    if (mesh.ok() && report.num_tets != mesh.value().num_tets())
        finding("tetrahedralize's report counts other tets than it returns");
    return mesh;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    set_thread_count(1);  // one core per fuzzer process; the image does not depend on it
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    FuzzedDataProvider in(data, size);
    const auto mode = in.ConsumeIntegral<std::uint8_t>();
    const bool via_unstructured = (mode & 1) != 0;
    static constexpr std::array<SortMethod, 4> kMethods = {
        SortMethod::kMpvo, SortMethod::kMpvoNonConvex, SortMethod::kExact, SortMethod::kCentroid};
    const SortMethod method = kMethods[(mode >> 1) & 3];
    static constexpr std::array<Integrator, 4> kIntegrators = {
        Integrator::kExact, Integrator::kExpTexture, Integrator::kPreintegrated,
        Integrator::kExact};
    const Integrator integrator = kIntegrators[(mode >> 3) & 3];
    const bool orthographic = (mode >> 5) & 1;
    const bool inside = (mode >> 6) & 1;

    auto created = fuzz_mesh(in, via_unstructured);
    if (!created.ok()) {
        (void)created.error().to_string();
        return 0;
    }
    const TetMesh& mesh = created.value();
    check_mesh(mesh);
    auto adjacency = build_face_adjacency(mesh);
    if (!adjacency.ok()) {
        (void)adjacency.error().to_string();
        return 0;
    }
    check_adjacency(mesh, adjacency.value());
    (void)check_convexity(mesh, adjacency.value());

    const Camera camera =
        random_view(mesh.bounds(), in.ConsumeIntegral<std::uint64_t>(), orthographic, inside);
    if (!check_camera(camera).ok()) return 0;
    const CameraFrame frame(camera, 16, 16);
    const SortView view = SortView::from_camera(frame);

    VisibilitySorter sorter;
    std::vector<CellId> order;
    SortOptions sort_options;
    sort_options.max_fallback_cells = in.ConsumeIntegralInRange<std::size_t>(0, 64);
    (void)sorter.sort(mesh, adjacency.value(), view, method, order, sort_options);
    check_permutation(mesh, order);
    if (in.ConsumeBool()) {
        std::vector<CellId> all(mesh.num_real_tets()), pairwise;
        for (std::size_t t = 0; t < all.size(); ++t) all[t] = static_cast<CellId>(t);
        SortStats stats;
        pairwise_exact_order(mesh, all, view, pairwise, stats);
        check_permutation(mesh, pairwise);
    }
    const OrderCheck verified = check_order(mesh, order, frame);
    if (verified.missing_cells != 0)
        finding("check_order finds cells missing from a complete order");

    const auto tf = fuzz_tf(in);
    std::vector<float> scalar(mesh.num_points());
    for (float& s : scalar) s = static_cast<float>(fuzz_double(in));
    for (float& s : scalar) {
        if (!std::isfinite(s)) s = 0.0f;  // scalars are finite where renders are made
    }
    // kPreintegrated takes 0.1 s to build: one shader, on the default transfer function, for
    // every input (it takes segments of any length).
    static const SegmentShader preintegrated(*default_tf(), Integrator::kPreintegrated, 1.0);
    std::unique_ptr<SegmentShader> own;
    const SegmentShader* shader = &preintegrated;
    if (integrator != Integrator::kPreintegrated) {
        own = std::make_unique<SegmentShader>(*tf, integrator, longest_edge(mesh));
        shader = own.get();
    }
    RenderInputs inputs;
    inputs.mesh = &mesh;
    inputs.scalar = scalar;
    inputs.order = order;
    inputs.shader = shader;
    inputs.camera = &frame;
    inputs.background = Vec3(in.ConsumeProbability<double>(), in.ConsumeProbability<double>(),
                             in.ConsumeProbability<double>());
    RenderStats stats;
    const Image image = render_projected_tetrahedra(inputs, &stats);
    if (image.width != 16 || image.height != 16 || image.pixels.size() != 256)
        finding("image size");
    for (const Vec3f& p : image.pixels) {
        for (int c = 0; c < 3; ++c) {
            if (!std::isfinite(p[c]) || p[c] < -1e-4f || p[c] > 1.0001f) {
                std::fprintf(stderr, "  pixel %zu: %g %g %g\n",
                             static_cast<std::size_t>(&p - image.pixels.data()), p[0], p[1], p[2]);
                finding("a pixel is not finite or outside [0, 1]");
            }
        }
    }
    return 0;
}
