#include <core/stopwatch.h>
#include <pipeline/progressive_render.h>
#include <project/pbvr/pbvr_common.h>
#include <project/segment_merge.h>
#include <project/segment_shader.h>

#include <algorithm>

namespace tr {

// A volume's pre-integrated shader (as `tetrender render` makes it), kept while its transfer
// function stays.
struct ProgressiveRender::Shader {
    std::shared_ptr<const TransferFunction> tf;  // the shader refers to it
    std::uint64_t tf_version = 0;
    SegmentShader shader;
};

struct ProgressiveRender::KeptSet {
    ObjectParticleSet set;
    std::uint64_t tf_version = 0;  // the transfer function the set was last made to follow
    int repetitions = 0;
};

ProgressiveRender::ProgressiveRender(std::vector<OpaqueSurface> opaque, ProgressiveOptions options)
    : opaque_(std::move(opaque)), options_(std::move(options)) {}

ProgressiveRender::~ProgressiveRender() = default;

void ProgressiveRender::begin(ProgressiveView view) {
    const auto start = SteadyClock::now();
    view_ = std::move(view);
    frame_.emplace(view_.camera, view_.width, view_.height);
    layer_ = OpaqueLayer{};
    if (!opaque_.empty()) layer_ = render_opaque(opaque_, *frame_, view_.background);
    scene_ = VolumeScene{};
    stats_ = ProgressiveStats{};
    for (const ProgressiveVolume& v : view_.volumes) {
        scene_.volumes.push_back({v.mesh, *v.scalar, v.tf.get(), nullptr});
        stats_.cells += v.mesh->num_real_tets();
    }
    static_cast<View&>(scene_) = view_over(*frame_, view_.background, layer_);
    shaders_.resize(std::max(shaders_.size(), view_.volumes.size()));
    sum_.assign(static_cast<std::size_t>(view_.width) * view_.height * 3, 0.0);
    exact_.reset();
    total_batch_ms_ = 0;
    // The kept particles hold for the same scalar and a camera they are reusable for.
    const bool reuse = view_.volumes.size() == 1 && !kept_.empty() &&
                       kept_scalar_version_ == view_.volumes[0].scalar_version &&
                       std::all_of(kept_.begin(), kept_.end(),
                                   [&](const KeptSet& k) { return k.set.reusable_for(*frame_); });
    if (!reuse) kept_.clear();
    kept_scalar_version_ = view_.volumes[0].scalar_version;
    replayed_ = 0;
    count_kept();
    stats_.setup_ms = ms_since(start);
}

int ProgressiveRender::most_repetitions(ParticleMethod method, int cap) const {
    const int level = method == ParticleMethod::kPbvrObject ? options_.object.subpixel_level : 1;
    const double per_repetition = static_cast<double>(view_.width) * view_.height * level * level;
    return static_cast<int>(
        std::clamp(kMaxParticleSamples / per_repetition, 1.0, static_cast<double>(cap)));
}

const SegmentShader& ProgressiveRender::shader_of(std::size_t volume) {
    const ProgressiveVolume& v = view_.volumes[volume];
    std::unique_ptr<Shader>& cache = shaders_[volume];
    if (!cache || cache->tf_version != v.tf_version || cache->tf != v.tf) {
        cache.reset();  // the old table goes before the new one is made
        cache.reset(new Shader{v.tf, v.tf_version,
                               SegmentShader(*v.tf, Integrator::kPreintegrated, v.longest_edge)});
    }
    return cache->shader;
}

Status ProgressiveRender::add_batch(ParticleMethod method, int repetitions, std::uint64_t seed,
                                    int preview_scale) {
    const auto start = SteadyClock::now();
    Image image;
    int drawn = repetitions;
    if (method == ParticleMethod::kPbvrImage) {
        kept_.clear();
        ImagePbvrOptions options = options_.image;
        options.repetitions = repetitions;
        options.seed = seed;
        image = draw_image_batch(options, preview_scale);
    } else {
        TR_TRY(image, draw_object_batch(repetitions, seed, drawn));
    }
    accumulate(image, drawn);
    stats_.preview_scale = method == ParticleMethod::kPbvrImage ? preview_scale : 1;
    stats_.batch_ms = ms_since(start);
    total_batch_ms_ += stats_.batch_ms;
    stats_.mean_batch_ms = total_batch_ms_ / stats_.batches;
    count_kept();
    return {};
}

Image ProgressiveRender::draw_image_batch(const ImagePbvrOptions& options, int scale) {
    // One volume: its segments' mean colours (pbvr_image.h, inverse-CDF depth), as the pipeline
    // draws it; several: none (their segments overlap on a ray: each particle's own colour).
    for (VolumeData& v : scene_.volumes) v.shader = nullptr;
    if (scene_.volumes.size() == 1 && options.depth == ParticleDepth::kInverseCdf)
        scene_.volumes[0].shader = &shader_of(0);
    ImagePbvrStats image_stats;
    Image image;
    if (scale <= 1) {
        image = render_image_pbvr(scene_, options, &image_stats);
    } else {
        const int width = view_.width, height = view_.height;
        const int w = std::max(1, (width + scale - 1) / scale);
        const int h = std::max(1, (height + scale - 1) / scale);
        const CameraFrame small_frame(view_.camera, w, h);
        OpaqueLayer small_layer;
        if (!opaque_.empty()) small_layer = render_opaque(opaque_, small_frame, view_.background);
        VolumeScene small_scene = scene_;
        static_cast<View&>(small_scene) = view_over(small_frame, view_.background, small_layer);
        const Image small = render_image_pbvr(small_scene, options, &image_stats);
        image = Image(width, height);  // nearest: each small pixel covers scale x scale
        for (int y = 0; y < height; ++y) {
            for (int x = 0; x < width; ++x) {
                image.pixels[static_cast<std::size_t>(y) * width + x] =
                    small.pixels[static_cast<std::size_t>(std::min(y * h / height, h - 1)) * w +
                                 std::min(x * w / width, w - 1)];
            }
        }
    }
    stats_.particles += image_stats.particles;
    stats_.fragments = image_stats.fragments;
    return image;
}

Result<Image> ProgressiveRender::draw_object_batch(int repetitions, std::uint64_t seed,
                                                   int& drawn) {
    if (replayed_ < kept_.size()) {
        // A kept set: retargeted to a new transfer function, drawn again.
        KeptSet& kept = kept_[replayed_++];
        if (kept.tf_version != view_.volumes[0].tf_version) {
            stats_.retargeted_cells = std::max(stats_.retargeted_cells, kept.set.retarget(scene_));
            kept.tf_version = view_.volumes[0].tf_version;
        }
        drawn = kept.repetitions;
        stats_.reused_repetitions += drawn;
        stats_.particles += kept.set.size();
        return kept.set.render(scene_);
    }
    ObjectPbvrOptions options = options_.object;
    options.repetitions = repetitions;
    options.seed = seed;
    const ObjectPbvrPlan plan = plan_object_pbvr(scene_, options);
    if (plan.candidates > kMaxObjectCandidates) {
        return make_error(ErrorCode::kInvalidArgument,
                          "pbvr-object: too many particles for this view (the camera is inside or "
                          "very near the volume); move it out, or use pbvr-image");
    }
    ObjectParticleSet set = ObjectParticleSet::generate(scene_, options, &plan);
    Image image = set.render(scene_);
    stats_.particles += set.size();
    std::size_t kept_bytes = 0;
    for (const KeptSet& k : kept_) kept_bytes += k.set.byte_size();
    // Kept while every earlier batch of this view is (batch b: seed + b, in order).
    if (replayed_ == kept_.size() && kept_bytes + set.byte_size() <= options_.max_kept_bytes) {
        kept_.push_back({std::move(set), view_.volumes[0].tf_version, repetitions});
        replayed_ = kept_.size();
    }
    drawn = repetitions;
    return image;
}

void ProgressiveRender::add_picture(const Image& image, int repetitions) {
    accumulate(image, repetitions);
}

void ProgressiveRender::accumulate(const Image& image, int repetitions) {
    const double weight = repetitions;
    for (std::size_t p = 0; p < image.pixels.size(); ++p) {
        for (int k = 0; k < 3; ++k) sum_[3 * p + k] += weight * image.pixels[p][k];
    }
    stats_.repetitions += repetitions;
    ++stats_.batches;
}

void ProgressiveRender::draw_exact() {
    const auto start = SteadyClock::now();
    for (std::size_t v = 0; v < scene_.volumes.size(); ++v)
        scene_.volumes[v].shader = &shader_of(v);
    SegmentMergeStats merge;
    exact_ = std::make_shared<const Image>(render_segment_merge(scene_, &merge));
    stats_.exact = true;
    stats_.fragments = merge.fragments;
    stats_.overlap_intervals = merge.overlap_intervals;
    stats_.exact_ms = ms_since(start);
}

std::shared_ptr<const Image> ProgressiveRender::picture() const {
    if (exact_) return exact_;
    if (stats_.repetitions == 0) return nullptr;
    auto image = std::make_shared<Image>(view_.width, view_.height);
    const double inverse = 1.0 / stats_.repetitions;
    for (std::size_t p = 0; p < image->pixels.size(); ++p) {
        image->pixels[p] = Vec3f(static_cast<float>(sum_[3 * p] * inverse),
                                 static_cast<float>(sum_[3 * p + 1] * inverse),
                                 static_cast<float>(sum_[3 * p + 2] * inverse));
    }
    return image;
}

View ProgressiveRender::view() const { return static_cast<const View&>(scene_); }

void ProgressiveRender::release_memory() {
    kept_.clear();
    replayed_ = 0;
    for (auto& s : shaders_) s.reset();
    for (VolumeData& v : scene_.volumes) v.shader = nullptr;
    count_kept();
}

void ProgressiveRender::count_kept() {
    stats_.kept_bytes = 0;
    for (const KeptSet& k : kept_) stats_.kept_bytes += k.set.byte_size();
    stats_.kept_sets = static_cast<int>(kept_.size());
}

}  // namespace tr
