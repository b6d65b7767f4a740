#include <apps/viewer/pbvr_worker.h>
#include <core/stopwatch.h>
#include <pipeline/loaded_mesh.h>
#include <pipeline/methods/splat_method.h>
#include <project/pbvr/pbvr_common.h>
#include <project/segment_shader.h>

#include <algorithm>
#include <chrono>
#include <new>

namespace tr::viewer {

struct PbvrWorker::KeptBatch {
    ObjectParticleSet set;
    std::uint64_t tf_version = 0;  // the transfer function the set was last made to follow
    int repetitions = 0;
};

struct PbvrWorker::ShaderCache {
    std::shared_ptr<const TransferFunction> tf;  // the shader refers to it
    std::uint64_t tf_version = 0;
    SegmentShader shader;
};

// The request being accumulated. Lives in the worker's loop and never moves: `scene` points
// into it.
struct PbvrWorker::Job {
    PbvrRequest request;
    std::uint64_t id = 0;
    bool fresh = false;   // begin() not yet called
    bool active = false;  // a request has begun
    std::optional<CameraFrame> frame;
    OpaqueLayer opaque;
    VolumeScene scene;
    std::vector<double> sum;  // sum over batches of the batch's mean x its repetitions
    PbvrFrame stats;
    std::size_t replayed = 0;  // kept particle sets drawn for this request
    double total_batch_ms = 0;
};

PbvrWorker::PbvrWorker(const TetMesh& mesh, std::vector<OpaqueSurface> opaque, double longest_edge,
                       PbvrSettings settings)
    : mesh_(mesh),
      opaque_(std::move(opaque)),
      longest_edge_(longest_edge),
      settings_(std::move(settings)),
      target_(std::clamp(settings_.repetitions, 1, kMaxRepetitions)) {
    thread_ = std::thread([this] { run(); });
}

PbvrWorker::~PbvrWorker() { stop_and_join(); }

std::uint64_t PbvrWorker::request(PbvrRequest request) { return post(std::move(request)); }

void PbvrWorker::set_target(int repetitions) {
    {
        std::lock_guard lock(mutex_);
        target_ = std::clamp(repetitions, 1, kMaxRepetitions);
        if (latest_) latest_->finished = latest_->repetitions >= target_;
    }
    wake_.notify_all();
    done_.notify_all();
}

int PbvrWorker::target() const {
    std::lock_guard lock(mutex_);
    return target_;
}

std::optional<PbvrFrame> PbvrWorker::latest() const {
    std::lock_guard lock(mutex_);
    return latest_;
}

PbvrFrame PbvrWorker::wait_for(std::uint64_t request_id, int repetitions) {
    std::unique_lock lock(mutex_);
    done_.wait(lock, [&] {
        if (!latest_) return false;
        if (latest_->request_id > request_id) return true;
        return latest_->request_id == request_id && (latest_->repetitions >= repetitions ||
                                                     latest_->finished || !latest_->error.empty());
    });
    return *latest_;
}

void PbvrWorker::run() {
    Job job;
    for (;;) {
        int target = 0;
        {
            std::unique_lock lock(mutex_);
            wake_.wait(lock, [&] {
                return stop_ || pending_.has_value() ||
                       (job.active && job.stats.error.empty() && job.stats.repetitions < target_);
            });
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
            run_batch(job, target);
        } catch (const std::bad_alloc&) {
            kept_.clear();
            shader_.reset();
            job.stats.error = "out of memory while rendering particles";
        }
        publish(job);
    }
}

void PbvrWorker::begin(Job& job) {
    const auto start = std::chrono::steady_clock::now();
    job.fresh = false;
    job.active = true;
    const PbvrRequest& r = job.request;
    job.frame.emplace(r.camera, r.width, r.height);
    job.opaque = OpaqueLayer{};
    if (!opaque_.empty()) job.opaque = render_opaque(opaque_, *job.frame, r.background);
    job.scene = VolumeScene{};
    job.scene.volumes.push_back({&mesh_, *r.scalar, r.tf.get(), nullptr});
    static_cast<View&>(job.scene) = view_over(*job.frame, r.background, job.opaque);
    job.sum.assign(static_cast<std::size_t>(r.width) * r.height * 3, 0.0);
    job.stats = PbvrFrame{};
    job.stats.request_id = job.id;
    job.stats.method = r.method;
    job.stats.cells = mesh_.num_real_tets();
    job.replayed = 0;
    job.total_batch_ms = 0;
    if (r.method == ViewMethod::kPbvrImage) {
        kept_.clear();
        // The segments' mean colours (pbvr_image.h: with the inverse-CDF depth only), from the
        // pre-integrated table, made once per transfer function.
        if (settings_.image.depth == ParticleDepth::kInverseCdf) {
            if (!shader_ || shader_->tf_version != r.tf_version) {
                shader_.reset();
                shader_.reset(new ShaderCache{
                    r.tf, r.tf_version,
                    SegmentShader(*r.tf, Integrator::kPreintegrated, longest_edge_)});
            }
            job.scene.volumes[0].shader = &shader_->shader;
        }
    } else if (r.method == ViewMethod::kPbvrObject) {
        // The kept particles hold for the same scalar and a camera they are reusable for.
        const bool reuse = !kept_.empty() && kept_scalar_version_ == r.scalar_version &&
                           std::all_of(kept_.begin(), kept_.end(), [&](const KeptBatch& k) {
                               return k.set.reusable_for(*job.frame);
                           });
        if (!reuse) kept_.clear();
        kept_scalar_version_ = r.scalar_version;
    }
    job.stats.setup_ms = ms_since(start);
}

void PbvrWorker::run_batch(Job& job, int target) {
    const auto start = std::chrono::steady_clock::now();
    const PbvrRequest& r = job.request;
    PbvrFrame& stats = job.stats;
    const std::uint64_t seed = settings_.seed + static_cast<std::uint64_t>(stats.batches);
    // The repetitions of a new batch: up to the target, within the library's limit on work.
    const int level = r.method == ViewMethod::kPbvrObject ? settings_.object.subpixel_level : 1;
    const double per_repetition = static_cast<double>(r.width) * r.height * level * level;
    const int most = static_cast<int>(
        std::clamp(kMaxParticleSamples / per_repetition, 1.0, static_cast<double>(kMaxBatch)));
    const int repetitions =
        std::clamp(std::min(settings_.batch_for(r.method), target - stats.repetitions), 1, most);
    Image image;
    int drawn = repetitions;
    if (r.method == ViewMethod::kSplat) {
        // One picture is the whole of it: it counts for every repetition still wanted.
        SplatPicture picture;
        picture.mesh = &mesh_;
        picture.points = settings_.splat_points;
        picture.scalar = *r.scalar;
        picture.tf = r.tf.get();
        picture.view = view_over(*job.frame, r.background, job.opaque);
        picture.where = "splat";
        SplatSettings splat = settings_.splat;
        splat.frame = r.splat_frame;
        auto made = render_splat_picture(picture, splat);
        if (!made.ok()) {
            stats.error = made.error().to_string();
            return;
        }
        image = std::move(made).value();
        drawn = std::max(target - stats.repetitions, 1);
    } else if (r.method == ViewMethod::kPbvrImage) {
        ImagePbvrOptions options = settings_.image;
        options.repetitions = repetitions;
        options.seed = seed;
        ImagePbvrStats image_stats;
        image = render_image_pbvr(job.scene, options, &image_stats);
        stats.particles += image_stats.particles;
    } else if (job.replayed < kept_.size()) {
        // A kept set: retargeted to a new transfer function, drawn again.
        KeptBatch& kept = kept_[job.replayed++];
        if (kept.tf_version != r.tf_version) {
            stats.retargeted_cells = std::max(stats.retargeted_cells, kept.set.retarget(job.scene));
            kept.tf_version = r.tf_version;
        }
        image = kept.set.render(job.scene);
        drawn = kept.repetitions;
        stats.reused_repetitions += drawn;
        stats.particles += kept.set.size();
    } else {
        ObjectPbvrOptions options = settings_.object;
        options.repetitions = repetitions;
        options.seed = seed;
        const ObjectPbvrPlan plan = plan_object_pbvr(job.scene, options);
        if (plan.candidates > kMaxObjectCandidates) {
            stats.error =
                "pbvr-object: too many particles for this view (the camera is inside or very "
                "near the volume); move it out, or use pbvr-image";
            return;
        }
        ObjectParticleSet set = ObjectParticleSet::generate(job.scene, options, &plan);
        image = set.render(job.scene);
        stats.particles += set.size();
        std::size_t kept_bytes = 0;
        for (const KeptBatch& k : kept_) kept_bytes += k.set.byte_size();
        // Kept while every earlier batch of this view is (batch b: seed + b, in order).
        if (job.replayed == kept_.size() &&
            kept_bytes + set.byte_size() <= settings_.max_kept_bytes) {
            kept_.push_back({std::move(set), r.tf_version, repetitions});
            job.replayed = kept_.size();
        }
    }
    const double weight = drawn;
    for (std::size_t p = 0; p < image.pixels.size(); ++p) {
        for (int k = 0; k < 3; ++k) job.sum[3 * p + k] += weight * image.pixels[p][k];
    }
    stats.repetitions += drawn;
    ++stats.batches;
    stats.batch_ms = ms_since(start);
    job.total_batch_ms += stats.batch_ms;
    stats.mean_batch_ms = job.total_batch_ms / stats.batches;
}

void PbvrWorker::publish(Job& job) {
    PbvrFrame& stats = job.stats;
    if (stats.repetitions > 0) {
        const PbvrRequest& r = job.request;
        auto image = std::make_shared<Image>(r.width, r.height);
        const double inverse = 1.0 / stats.repetitions;
        for (std::size_t p = 0; p < image->pixels.size(); ++p) {
            image->pixels[p] = Vec3f(static_cast<float>(job.sum[3 * p] * inverse),
                                     static_cast<float>(job.sum[3 * p + 1] * inverse),
                                     static_cast<float>(job.sum[3 * p + 2] * inverse));
        }
        stats.image = std::move(image);
    }
    stats.kept_bytes = 0;
    for (const KeptBatch& k : kept_) stats.kept_bytes += k.set.byte_size();
    stats.kept_sets = static_cast<int>(kept_.size());
    {
        std::lock_guard lock(mutex_);
        stats.finished = stats.repetitions >= target_;
        latest_ = stats;
    }
    done_.notify_all();
    if (on_frame_) on_frame_();
}

}  // namespace tr::viewer
