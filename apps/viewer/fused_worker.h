#pragma once
// The viewer's fused rendering of a scene of several volumes (scene.md "Several volumes in one
// space") in a worker thread, on the CPU, through the library as `tetrender render` draws such
// a scene: image-space PBVR over all volumes at once (project/pbvr/pbvr_image.h: their particles
// compete for the nearest place), a batch of repetitions at a time accumulated while the view
// stays, and the exact fused picture (project/segment_merge.h: every pixel's segments of every
// volume merged by depth, overlaps integrated with summed extinction and emission). Projected
// tetrahedra cannot draw such a scene: the cells of intersecting meshes have no visibility order.
//
// A new request (camera, size, mode, any volume's scalar or transfer function) replaces the one
// in progress after its current batch or exact picture; the window never waits: it shows the
// latest picture. The pictures are the pipeline's progressive render's
// (pipeline/progressive_render.h); the worker decides when to draw which, and at what size.

#include <apps/viewer/request_worker.h>
#include <apps/viewer/view_method.h>
#include <core/camera.h>
#include <core/image.h>
#include <mesh/tet_mesh.h>
#include <pipeline/progressive_render.h>
#include <project/opaque_geometry.h>
#include <project/transfer_function.h>

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace tr::viewer {

enum class FusedMode {
    kProgressive,  // one batch of pbvr-image (a quick picture while the camera moves, at a
                   // fraction of the size that keeps it near kPreviewBudget), then, when no newer
                   // view has been asked for within kStillDelay, the exact picture
    kPbvrImage,    // pbvr-image batches accumulated up to the target's repetitions
    kExact,        // the exact fused picture alone
};

// "progressive", "pbvr-image", "exact".
std::string_view fused_mode_name(FusedMode mode);

// A volume's mesh (its real tets are drawn) and its longest edge (cpu_renderer.h), for the exact
// picture's shader.
struct FusedMesh {
    const TetMesh* mesh = nullptr;
    double longest_edge = 1;
};

// A volume's scalar (one per mesh point) and transfer function for one request.
struct FusedVolumeState {
    std::shared_ptr<const std::vector<float>> scalar;
    std::shared_ptr<const TransferFunction> tf;
    std::uint64_t tf_version = 0;  // changes whenever `tf` does (the exact picture's shader)
};

struct FusedRequest {
    FusedMode mode = FusedMode::kProgressive;
    Camera camera;
    int width = 0, height = 0;              // the picture, >= 1 each
    std::vector<FusedVolumeState> volumes;  // one per mesh, in order
    Vec3 background{0.0};
};

// The picture so far of one request (its counts and costs: ProgressiveStats; `exact`: `image` is
// the exact fused picture, else the pbvr-image mean).
struct FusedFrame : ProgressiveStats {
    std::shared_ptr<const Image> image;
    std::uint64_t request_id = 0;
    FusedMode mode = FusedMode::kProgressive;
    bool finished = false;  // nothing more to draw for this request until a new one
    std::string error;      // a batch failed (out of memory): nothing more for this request
};

// set_target (pbvr-image's target repetitions), target, latest, wait_for (kWaitFinished: the
// request's last picture) and set_on_frame: AccumulatingWorker (request_worker.h).
class FusedWorker : public AccumulatingWorker<FusedRequest, FusedFrame> {
  public:
    // Progressive mode: how long the view must stay after the quick picture before the exact
    // one (which cannot be interrupted) is begun.
    static constexpr std::chrono::milliseconds kStillDelay{200};
    // Progressive mode: what the quick picture should cost. It is drawn at 1 / scale of the
    // size (scale 1, 2, 3, 4, 6 or 8, nearest-upsampled), the smallest scale whose cost at the
    // last quick picture's rate per pixel stays within this.
    static constexpr std::chrono::milliseconds kPreviewBudget{120};

    // The meshes and the surfaces `opaque` points to must outlive the worker. `settings`: the
    // particle-based settings (target repetitions, batch, seed, pbvr-image's options).
    FusedWorker(std::vector<FusedMesh> meshes, std::vector<OpaqueSurface> opaque,
                PbvrSettings settings);
    ~FusedWorker();  // waits for the batch in progress
    FusedWorker(const FusedWorker&) = delete;
    FusedWorker& operator=(const FusedWorker&) = delete;

    // Asks for `request`'s view (request.volumes: one per mesh); returns its id (increasing).
    std::uint64_t request(FusedRequest request);

    const PbvrSettings& settings() const { return settings_; }
    std::size_t num_volumes() const { return meshes_.size(); }

  private:
    bool finished_at(const FusedFrame& frame, int target) const override;
    void begin(const FusedRequest& request) override;
    void step(Job& job, int target) override;  // one batch, or the exact picture
    FusedFrame frame_of(const Job& job) const override;
    void wait_before_step(std::unique_lock<std::mutex>& lock, const Job& job) override;

    const std::vector<FusedMesh> meshes_;
    const PbvrSettings settings_;
    double preview_ms_per_pixel_ = 0;  // worker thread only: the last quick picture's
};

}  // namespace tr::viewer
