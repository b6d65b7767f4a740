#include <apps/viewer/fused_worker.h>
#include <core/stopwatch.h>
#include <pipeline/loaded_mesh.h>
#include <project/pbvr/pbvr_common.h>
#include <project/pbvr/pbvr_image.h>
#include <project/segment_merge.h>
#include <project/segment_shader.h>

#include <algorithm>
#include <chrono>
#include <new>

namespace tr::viewer {

std::string_view fused_mode_name(FusedMode mode) {
    switch (mode) {
        case FusedMode::kProgressive:
            return "progressive";
        case FusedMode::kPbvrImage:
            return "pbvr-image";
        case FusedMode::kExact:
            return "exact";
    }
    return "?";
}

// A volume's shader for the exact picture (the pre-integrated table, as `tetrender render`
// makes it), kept while the volume's transfer function stays.
struct FusedWorker::ShaderCache {
    std::shared_ptr<const TransferFunction> tf;  // the shader refers to it
    std::uint64_t tf_version = 0;
    SegmentShader shader;
};

// The request being drawn. Lives in the worker's loop and never moves: `scene` points into it.
struct FusedWorker::Job {
    FusedRequest request;
    std::uint64_t id = 0;
    bool fresh = false;   // begin() not yet called
    bool active = false;  // a request has begun
    std::optional<CameraFrame> frame;
    OpaqueLayer opaque;
    VolumeScene scene;
    std::vector<double> sum;  // sum over batches of the batch's mean x its repetitions
    std::shared_ptr<const Image> exact_image;
    FusedFrame stats;
    double total_batch_ms = 0;
    std::chrono::steady_clock::time_point published;  // the last picture
};

FusedWorker::FusedWorker(std::vector<FusedMesh> meshes, std::vector<OpaqueSurface> opaque,
                         PbvrSettings settings)
    : meshes_(std::move(meshes)),
      opaque_(std::move(opaque)),
      settings_(std::move(settings)),
      target_(std::clamp(settings_.repetitions, 1, kMaxRepetitions)) {
    shaders_.resize(meshes_.size());
    thread_ = std::thread([this] { run(); });
}

FusedWorker::~FusedWorker() { stop_and_join(); }

std::uint64_t FusedWorker::request(FusedRequest request) { return post(std::move(request)); }

void FusedWorker::set_target(int repetitions) {
    {
        std::lock_guard lock(mutex_);
        target_ = std::clamp(repetitions, 1, kMaxRepetitions);
        if (latest_ && latest_->mode == FusedMode::kPbvrImage && latest_->error.empty())
            latest_->finished = latest_->repetitions >= target_;
    }
    wake_.notify_all();
    done_.notify_all();
}

int FusedWorker::target() const {
    std::lock_guard lock(mutex_);
    return target_;
}

std::optional<FusedFrame> FusedWorker::latest() const {
    std::lock_guard lock(mutex_);
    return latest_;
}

FusedFrame FusedWorker::wait_for(std::uint64_t request_id, int repetitions) {
    std::unique_lock lock(mutex_);
    done_.wait(lock, [&] {
        if (!latest_) return false;
        if (latest_->request_id > request_id) return true;
        return latest_->request_id == request_id &&
               (latest_->finished || !latest_->error.empty() ||
                (repetitions < kWaitFinished &&
                 (latest_->exact || latest_->repetitions >= repetitions)));
    });
    return *latest_;
}

bool FusedWorker::has_work(const Job& job, int target) const {
    if (!job.active || !job.stats.error.empty()) return false;
    switch (job.request.mode) {
        case FusedMode::kExact:
            return !job.stats.exact;
        case FusedMode::kPbvrImage:
            return job.stats.repetitions < target;
        case FusedMode::kProgressive:
            return !job.stats.exact;
    }
    return false;
}

void FusedWorker::run() {
    Job job;
    for (;;) {
        int target = 0;
        {
            std::unique_lock lock(mutex_);
            wake_.wait(lock,
                       [&] { return stop_ || pending_.has_value() || has_work(job, target_); });
            // Progressive: the exact picture (which cannot be interrupted) only once the camera
            // has been still for kStillDelay since the quick picture, so that a drag never
            // waits for one.
            if (!stop_ && !pending_ && job.request.mode == FusedMode::kProgressive &&
                job.stats.repetitions > 0) {
                wake_.wait_until(lock, job.published + kStillDelay,
                                 [&] { return stop_ || pending_.has_value(); });
            }
            if (stop_) return;
            if (pending_) {
                job.request = std::move(pending_->first);
                job.id = pending_->second;
                job.fresh = true;
                pending_.reset();
            }
            target = target_;
        }
        try {
            if (job.fresh) begin(job);
            step(job, target);
        } catch (const std::bad_alloc&) {
            for (auto& s : shaders_) s.reset();
            job.stats.error = "out of memory while drawing the fused picture";
        }
        publish(job);
    }
}

void FusedWorker::begin(Job& job) {
    const auto start = std::chrono::steady_clock::now();
    job.fresh = false;
    job.active = true;
    const FusedRequest& r = job.request;
    job.frame.emplace(r.camera, r.width, r.height);
    job.opaque = OpaqueLayer{};
    if (!opaque_.empty()) job.opaque = render_opaque(opaque_, *job.frame, r.background);
    job.scene = VolumeScene{};
    for (std::size_t v = 0; v < meshes_.size(); ++v) {
        job.scene.volumes.push_back(
            {meshes_[v].mesh, *r.volumes[v].scalar, r.volumes[v].tf.get(), nullptr});
    }
    static_cast<View&>(job.scene) = view_over(*job.frame, r.background, job.opaque);
    job.sum.assign(static_cast<std::size_t>(r.width) * r.height * 3, 0.0);
    job.exact_image.reset();
    job.stats = FusedFrame{};
    job.stats.request_id = job.id;
    job.stats.mode = r.mode;
    job.total_batch_ms = 0;
    job.stats.setup_ms = ms_since(start);
}

void FusedWorker::step(Job& job, int target) {
    const auto start = std::chrono::steady_clock::now();
    const FusedRequest& r = job.request;
    FusedFrame& stats = job.stats;
    const bool exact =
        r.mode == FusedMode::kExact || (r.mode == FusedMode::kProgressive && stats.repetitions > 0);
    if (exact) {
        // Every volume's shader, as the pipeline makes it for the segment merge.
        for (std::size_t v = 0; v < meshes_.size(); ++v) {
            const FusedVolumeState& state = r.volumes[v];
            std::unique_ptr<ShaderCache>& cache = shaders_[v];
            if (!cache || cache->tf_version != state.tf_version || cache->tf != state.tf) {
                cache.reset();
                cache.reset(new ShaderCache{
                    state.tf, state.tf_version,
                    SegmentShader(*state.tf, Integrator::kPreintegrated, meshes_[v].longest_edge)});
            }
            job.scene.volumes[v].shader = &cache->shader;
        }
        SegmentMergeStats merge;
        job.exact_image = std::make_shared<const Image>(render_segment_merge(job.scene, &merge));
        stats.exact = true;
        stats.fragments = merge.fragments;
        stats.overlap_intervals = merge.overlap_intervals;
        stats.exact_ms = ms_since(start);
        return;
    }
    // pbvr-image: no shaders for several volumes (their segments overlap on a ray: the
    // particle's own colour is drawn), as the pipeline renders them.
    for (VolumeData& v : job.scene.volumes) v.shader = nullptr;
    const double per_repetition = static_cast<double>(r.width) * r.height;
    const int most = static_cast<int>(
        std::clamp(kMaxParticleSamples / per_repetition, 1.0, static_cast<double>(kMaxBatch)));
    const int batch = settings_.batch_for(ViewMethod::kPbvrImage);
    const int repetitions = r.mode == FusedMode::kProgressive
                                ? std::clamp(batch, 1, most)
                                : std::clamp(std::min(batch, target - stats.repetitions), 1, most);
    ImagePbvrOptions options = settings_.image;
    options.repetitions = repetitions;
    options.seed = settings_.seed + static_cast<std::uint64_t>(stats.batches);
    ImagePbvrStats image_stats;
    // Progressive: the quick picture at 1 / scale of the size, so that it costs about
    // kPreviewBudget at the last one's rate (its cost is mostly the segments on the pixel rays).
    int scale = 1;
    if (r.mode == FusedMode::kProgressive) {
        const double full_ms = preview_ms_per_pixel_ * r.width * r.height;
        for (int f : {2, 3, 4, 6, 8}) {
            if (full_ms / (scale * scale) <= kPreviewBudget.count()) break;
            scale = f;
        }
    }
    stats.preview_scale = scale;
    Image image;
    if (scale == 1) {
        image = render_image_pbvr(job.scene, options, &image_stats);
    } else {
        const int w = std::max(1, (r.width + scale - 1) / scale);
        const int h = std::max(1, (r.height + scale - 1) / scale);
        const CameraFrame frame(r.camera, w, h);
        OpaqueLayer opaque;
        VolumeScene scene = job.scene;
        if (!opaque_.empty()) opaque = render_opaque(opaque_, frame, r.background);
        static_cast<View&>(scene) = view_over(frame, r.background, opaque);
        const Image small = render_image_pbvr(scene, options, &image_stats);
        image = Image(r.width, r.height);  // nearest: each small pixel covers scale x scale
        for (int y = 0; y < r.height; ++y) {
            for (int x = 0; x < r.width; ++x) {
                image.pixels[static_cast<std::size_t>(y) * r.width + x] =
                    small.pixels[static_cast<std::size_t>(std::min(y * h / r.height, h - 1)) * w +
                                 std::min(x * w / r.width, w - 1)];
            }
        }
    }
    if (r.mode == FusedMode::kProgressive) {
        preview_ms_per_pixel_ =
            ms_since(start) * scale * scale / (static_cast<double>(r.width) * r.height);
    }
    stats.particles += image_stats.particles;
    stats.fragments = image_stats.fragments;
    for (std::size_t p = 0; p < image.pixels.size(); ++p) {
        for (int k = 0; k < 3; ++k) job.sum[3 * p + k] += repetitions * double(image.pixels[p][k]);
    }
    stats.repetitions += repetitions;
    ++stats.batches;
    stats.batch_ms = ms_since(start);
    job.total_batch_ms += stats.batch_ms;
    stats.mean_batch_ms = job.total_batch_ms / stats.batches;
}

void FusedWorker::publish(Job& job) {
    FusedFrame& stats = job.stats;
    job.published = std::chrono::steady_clock::now();
    if (job.exact_image) {
        stats.image = job.exact_image;
    } else if (stats.repetitions > 0) {
        const FusedRequest& r = job.request;
        auto image = std::make_shared<Image>(r.width, r.height);
        const double inverse = 1.0 / stats.repetitions;
        for (std::size_t p = 0; p < image->pixels.size(); ++p) {
            image->pixels[p] = Vec3f(static_cast<float>(job.sum[3 * p] * inverse),
                                     static_cast<float>(job.sum[3 * p + 1] * inverse),
                                     static_cast<float>(job.sum[3 * p + 2] * inverse));
        }
        stats.image = std::move(image);
    }
    {
        std::lock_guard lock(mutex_);
        stats.finished = !has_work(job, target_);
        latest_ = stats;
    }
    done_.notify_all();
    if (on_frame_) on_frame_();
}

}  // namespace tr::viewer
