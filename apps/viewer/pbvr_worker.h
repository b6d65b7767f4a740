#pragma once
// The viewer's particle-based modes in a worker thread: the pipeline's progressive render
// (pipeline/progressive_render.h: pbvr-image or pbvr-object as `tetrender render` draws them)
// renders the requested view a batch of repetitions at a time on the CPU, each batch with its own
// seed, and the batches are accumulated in floating point while the view stays; a new request
// (camera, size, scalar, transfer function or method changed) restarts the accumulation after the
// batch in progress. The window never waits for it: it shows the latest accumulated picture.
//
// Splatting (ViewMethod::kSplat) runs here too: one request is one picture
// (pipeline/methods/splat_method.h render_splat_picture, as `tetrender render --method splat` draws
// it), finished at once; with vector splats the request names the frame of the texture cycle.
//
// O-PBVR keeps the particles of a view's first batches (up to PbvrSettings::max_kept_bytes): when
// a new request differs only in its transfer function, or turns an orthographic camera, the kept
// particles are drawn again (after retarget() for a new function) instead of being generated
// anew; a perspective camera that moves, a new scalar or a new size generates them again.

#include <apps/viewer/request_worker.h>
#include <apps/viewer/view_method.h>
#include <core/camera.h>
#include <core/image.h>
#include <mesh/tet_mesh.h>
#include <pipeline/progressive_render.h>
#include <project/opaque_geometry.h>
#include <project/transfer_function.h>

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace tr::viewer {

// The view to accumulate.
struct PbvrRequest {
    ViewMethod method = ViewMethod::kPbvrImage;  // kPbvrImage, kPbvrObject or kSplat
    Camera camera;
    int width = 0, height = 0;                         // the picture, >= 1 each
    std::shared_ptr<const std::vector<float>> scalar;  // one per mesh point
    std::uint64_t scalar_version = 0;                  // changes whenever `scalar` does
    std::shared_ptr<const TransferFunction> tf;
    std::uint64_t tf_version = 0;  // changes whenever `tf` does
    Vec3 background{0.0};
    std::int64_t splat_frame = 0;  // splat with vectors: the frame of the texture cycle
};

// The accumulation so far of one request (its counts and costs: ProgressiveStats).
struct PbvrFrame : ProgressiveStats {
    std::shared_ptr<const Image> image;  // the mean of the repetitions so far
    std::uint64_t request_id = 0;        // the request it answers
    ViewMethod method = ViewMethod::kPbvrImage;
    bool finished = false;  // reached the target: the worker rests until the next request
    std::string error;      // the batch failed (out of memory): nothing more for this request
};

// set_target, target, latest, wait_for and set_on_frame: AccumulatingWorker (request_worker.h).
class PbvrWorker : public AccumulatingWorker<PbvrRequest, PbvrFrame> {
  public:
    // `mesh` (its real tets are drawn) and the surfaces `opaque` points to must outlive the
    // worker. `longest_edge`: the mesh's (cpu_renderer.h), for pbvr-image's shader.
    PbvrWorker(const TetMesh& mesh, std::vector<OpaqueSurface> opaque, double longest_edge,
               PbvrSettings settings);
    ~PbvrWorker();  // waits for the batch in progress
    PbvrWorker(const PbvrWorker&) = delete;
    PbvrWorker& operator=(const PbvrWorker&) = delete;

    // Asks for `request`'s view: it replaces a request not yet started, and the accumulation in
    // progress stops after its current batch. Returns the request's id (increasing).
    std::uint64_t request(PbvrRequest request);

    const PbvrSettings& settings() const { return settings_; }

  private:
    bool finished_at(const PbvrFrame& frame, int target) const override;
    void begin(const PbvrRequest& request) override;
    void step(Job& job, int target) override;  // one batch towards `target` repetitions
    PbvrFrame frame_of(const Job& job) const override;
    void draw_splat(Job& job, int target);

    const TetMesh& mesh_;
    const double longest_edge_;
    const PbvrSettings settings_;
};

}  // namespace tr::viewer
