#include <core/parallel.h>
#include <core/stopwatch.h>
#include <distributed/detail/collectives.h>
#include <distributed/detail/guarded.h>
#include <distributed/detail/icet_compositor.h>
#include <distributed/detail/shares.h>
#include <distributed/distributed_render.h>
#include <project/opaque_geometry.h>

#include <chrono>
#include <map>

namespace tr {

using namespace distributed_detail;

namespace {

using Clock = std::chrono::steady_clock;

// What the ranks cannot draw together yet (before anything is loaded).
Status check_distributable(const Scene& scene, const RenderOptions& options) {
    const std::string& method = scene.method_name();
    if (method != "projected-tetrahedra" && method != "pbvr-image" && method != "pbvr-object") {
        return make_error(ErrorCode::kUnsupported,
                          "$.method.name: '" + method +
                              "' is not drawn across ranks yet (projected-tetrahedra, "
                              "pbvr-image and pbvr-object are)",
                          scene.source);
    }
    if (scene.flow_volume) {
        return make_error(ErrorCode::kUnsupported,
                          "$.flow_volume: flow volumes are not drawn across ranks yet",
                          scene.source);
    }
    if (options.reference) {
        return make_error(ErrorCode::kUnsupported, "the reference ray caster runs in one process",
                          scene.source);
    }
    for (const OpaqueSpec& spec : scene.opaque) {
        if (!spec.surface && spec.file.empty()) {
            return make_error(ErrorCode::kUnsupported,
                              "$.opaque: a mesh's boundary or side sets are not drawn across "
                              "ranks yet (a surface file is)",
                              scene.source);
        }
    }
    return {};
}

// What identifies a scene's volumes as loaded (steps 1-3 are kept while it stays the same).
std::string volumes_key(const Scene& scene) {
    std::string key;
    for (const SceneVolume& v : scene.volumes) {
        key += v.mesh.string() + '|' + v.scalar + '|' + std::to_string(v.component) + '|' +
               std::to_string(v.time_step) + '|' +
               std::to_string(reinterpret_cast<std::uintptr_t>(v.tets.get())) + '|' +
               std::to_string(reinterpret_cast<std::uintptr_t>(v.data.get())) + ';';
    }
    return key;
}

// The scene this rank draws: its share of each volume that has one (the scalar already
// chosen), the PBVR seed made the rank's own (rank 0 keeps the scene's: one rank draws what
// one process draws).
Scene share_scene(const Scene& scene, const Shares& shares, int rank) {
    Scene local = scene;
    local.volumes.clear();
    for (std::size_t v = 0; v < scene.volumes.size(); ++v) {
        if (shares.meshes[v]->num_real_tets() == 0) continue;
        SceneVolume volume = scene.volumes[v];
        volume.tets = shares.meshes[v];
        volume.data = nullptr;
        volume.component = -1;  // the share's field has one component: the value itself
        local.volumes.push_back(std::move(volume));
    }
    const bool particles =
        scene.method_name() == "pbvr-image" || scene.method_name() == "pbvr-object";
    if (rank != 0 && particles) {
        const std::uint64_t seed =
            local.method->seed ? static_cast<std::uint64_t>(*local.method->seed) : 1;
        local.method->seed = static_cast<std::int64_t>(seed + 0x9E3779B97F4A7C15ull *
                                                                  static_cast<std::uint64_t>(rank));
    }
    return local;
}

// Premultiplied RGBA of a transparent render (the colour is already premultiplied).
std::vector<float> rgba_of(const RenderResult& result, int width, int height) {
    const std::size_t n = static_cast<std::size_t>(width) * height;
    std::vector<float> rgba(4 * n, 0.0f);
    if (result.image.pixels.size() != n) return rgba;
    for (std::size_t i = 0; i < n; ++i) {
        rgba[4 * i + 0] = result.image.pixels[i].r;
        rgba[4 * i + 1] = result.image.pixels[i].g;
        rgba[4 * i + 2] = result.image.pixels[i].b;
        rgba[4 * i + 3] = result.alpha[i];
    }
    return rgba;
}

// Every rank's notes on rank 0, each text once with the ranks that said it.
std::vector<std::string> gathered_notes(const std::vector<std::string>& mine, int rank) {
    std::vector<std::string> tagged;
    for (const std::string& note : mine) tagged.push_back(std::to_string(rank) + '\t' + note);
    std::map<std::string, std::string> ranks_of;
    std::vector<std::string> order;
    for (const std::string& entry : gather_to_root(tagged)) {
        const std::size_t tab = entry.find('\t');
        const std::string text = entry.substr(tab + 1);
        auto [it, added] = ranks_of.try_emplace(text, entry.substr(0, tab));
        if (added) {
            order.push_back(text);
        } else {
            it->second += ", " + entry.substr(0, tab);
        }
    }
    std::vector<std::string> notes;
    for (const std::string& text : order) {
        const bool several = ranks_of[text].find(',') != std::string::npos;
        notes.push_back((several ? "ranks " : "rank ") + ranks_of[text] + ": " + text);
    }
    return notes;
}

// What one rank measured of one render, for the stats rank 0 collects.
struct RankRender {
    RenderResult drawn;  // this rank's transparent picture and its pipeline's stats
    double render_ms = 0;
    double composite_ms = 0;  // the IceT call's wall time, waiting for the others included
    CompositeStats icet;
    bool drew = false;  // whether this rank had a share to draw
};

// Rank 0's stats: the run's, then one number per rank for each measure (`shares` zeroed when
// they were kept from an earlier render). Collective.
NamedStats collect_stats(const MpiWorld& world, const Scene& scene, const ShareStats& s, bool fresh,
                         const RankRender& rank) {
    NamedStats out;
    const NamedStats& drawn = rank.drawn.stats;
    const bool exact = all_ranks(!rank.drew || drawn.find("sort_exact") == nullptr ||
                                 std::get<bool>(*drawn.find("sort_exact")));
    const StatValue* compositing = drawn.find("compositing");
    const std::int64_t merged_ranks =
        sum_over_ranks(compositing && std::get<std::string>(*compositing) == "merged" ? 1 : 0);
    const std::int64_t cut = sum_over_ranks(static_cast<std::int64_t>(s.tets_cut));
    const std::int64_t pieces = sum_over_ranks(static_cast<std::int64_t>(s.pieces_made));
    if (world.rank() == 0) {
        out.set("ranks", world.size());
        out.set("method", scene.method_name());
        out.set("reading", s.reading);
        out.set("volumes_kept", !fresh);
        out.set("tets_cut", cut);
        out.set("pieces_made", pieces);
        if (scene.method_name() == kDefaultMethod) out.set("sort_exact", exact);
        out.set("ranks_merged", merged_ranks);
        out.set("threads", thread_count());
        out.set("width", scene.width);
        out.set("height", scene.height);
    }
    const std::pair<const char*, double> per_rank[] = {
        {"files_read", static_cast<double>(s.files_read)},
        {"cells_read", static_cast<double>(s.cells_read)},
        {"cells", static_cast<double>(s.cells)},
        {"volume", s.volume},
        {"read_ms", s.read_ms},
        {"partition_ms", s.partition_ms},
        {"cut_ms", s.cut_ms},
        {"exchange_ms", s.exchange_ms},
        {"merge_ms", s.merge_ms},
        {"redistribute_ms", s.redistribute_ms},
        {"bytes_sent", static_cast<double>(s.bytes_sent)},
        {"adjacency_ms", drawn.number("adjacency_ms")},
        {"convexify_ms", drawn.number("convexify_ms")},
        {"shader_ms", drawn.number("shader_ms")},
        {"sort_ms", drawn.number("sort_ms")},
        {"raster_ms", drawn.number("raster_ms")},
        {"fragments", drawn.number("fragments")},
        {"render_ms", rank.render_ms},
        {"composite_ms", rank.composite_ms},
        {"icet_composite_ms", rank.icet.composite_ms},
        {"composite_bytes_sent", static_cast<double>(rank.icet.bytes_sent)},
    };
    for (const auto& [key, value] : per_rank) {
        std::vector<double> all = gather_to_root(value);
        if (world.rank() == 0) out.set(key, all);
    }
    return out;
}

// Rank 0's picture: the blend `rgba` (premultiplied) over the opaque surfaces' picture, or the
// background.
Result<Image> over_what_is_behind(Pipeline& pipeline, const Scene& scene, const CameraFrame& frame,
                                  const std::vector<float>& rgba) {
    Image behind(scene.width, scene.height, Vec3f(scene.background));
    if (!scene.opaque.empty()) {
        TR_TRY(const OpaqueSet opaque, pipeline.opaque(scene));
        behind = render_opaque(opaque.layers(), frame, scene.background).color;
    }
    Image picture(scene.width, scene.height);
    for (std::size_t i = 0; i < picture.pixels.size(); ++i) {
        const float transmitted = 1.0f - rgba[4 * i + 3];
        picture.pixels[i] =
            Vec3f(rgba[4 * i], rgba[4 * i + 1], rgba[4 * i + 2]) + transmitted * behind.pixels[i];
    }
    return picture;
}

}  // namespace

struct DistributedRenderer::Impl {
    const MpiWorld& world;
    PipelineOptions options;
    Pipeline pipeline;
    IcetCompositor compositor;
    std::string key;  // of the volumes `shares` holds
    std::unique_ptr<Shares> shares;

    Impl(const MpiWorld& w, PipelineOptions o) : world(w), options(o), pipeline(std::move(o)) {
        // Reading reports its progress (rank 0's: the others are given none by the program).
        if (!options.load.progress) options.load.progress = options.progress;
    }

    Result<DistributedResult> render(const Scene& scene, const RenderOptions& options);
    // Steps 4 and 5: this rank's picture, composited; the result on rank 0. `fresh`: this
    // render read and redistributed the volumes (their stats are reported).
    Result<DistributedResult> draw_and_composite(const Scene& scene, const RenderOptions& options,
                                                 bool fresh);
};

Result<DistributedResult> DistributedRenderer::Impl::render(const Scene& scene,
                                                            const RenderOptions& render_options) {
    RenderOptions transparent = render_options;
    transparent.transparent = true;
    TR_TRY_STATUS(world.agree(guarded([&]() -> Status {
        TR_TRY_STATUS(check_distributable(scene, render_options));
        return pipeline.check(scene, transparent);
    })));
    const std::string wanted = volumes_key(scene);
    const bool fresh = !shares || key != wanted;
    if (fresh) {
        shares.reset();
        pipeline.clear();
        TR_TRY(Shares made, read_and_redistribute(world, scene, options.load));
        shares = std::make_unique<Shares>(std::move(made));
        key = wanted;
    }
    return draw_and_composite(scene, transparent, fresh);
}

Result<DistributedResult> DistributedRenderer::Impl::draw_and_composite(
    const Scene& scene, const RenderOptions& options, bool fresh) {
    // 4. This rank's share drawn over transparent black.
    RankRender rank;
    auto start = Clock::now();
    const Scene local = share_scene(scene, *shares, world.rank());
    rank.drew = !local.volumes.empty();
    const Status rendered = guarded([&]() -> Status {
        if (!rank.drew) return {};
        TR_TRY(rank.drawn, pipeline.render(local, options));
        return {};
    });
    TR_TRY_STATUS(world.agree(rendered));
    rank.render_ms = ms_since(start);

    // 5. Blended in the boxes' order for this view, then over what lies behind the volume.
    const CameraFrame frame(scene.camera, scene.width, scene.height);
    const std::vector<float> rgba = rgba_of(rank.drawn, scene.width, scene.height);
    start = Clock::now();
    Result<std::vector<float>> blended = compositor.composite(
        rgba, scene.width, scene.height, nonzero_rect(rgba, scene.width, scene.height),
        shares->partition.front_to_back(frame), &rank.icet);
    TR_TRY_STATUS(world.agree(blended.ok() ? Status() : Status(blended.error())));
    rank.composite_ms = ms_since(start);
    DistributedResult result;
    const Status finished = guarded([&]() -> Status {
        if (world.rank() != 0) return {};
        TR_TRY(result.image, over_what_is_behind(pipeline, scene, frame, *blended));
        return {};
    });
    TR_TRY_STATUS(world.agree(finished));

    // The volumes' reading and redistribution, on the render that did them (zeros after).
    const ShareStats made = fresh ? shares->stats : ShareStats{.reading = shares->stats.reading};
    result.stats = collect_stats(world, scene, made, fresh, rank);
    std::vector<std::string> notes = gathered_notes(rank.drawn.notes, world.rank());
    if (world.rank() == 0) result.notes = std::move(notes);
    return result;
}

DistributedRenderer::DistributedRenderer(const MpiWorld& world, PipelineOptions options)
    : impl_(std::make_unique<Impl>(world, std::move(options))) {}

DistributedRenderer::~DistributedRenderer() = default;

Result<DistributedResult> DistributedRenderer::render(const Scene& scene,
                                                      const RenderOptions& options) {
    return impl_->render(scene, options);
}

}  // namespace tr
