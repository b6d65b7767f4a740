#pragma once
// What the viewer draws each frame: the mesh's volume in the sort worker's latest order for the
// view, or the flow volume; the transfer function rebuilt when the panel changed it; the frame
// redrawn only when something it shows changed; and which GL renderer holds the last frame.

#include <apps/viewer/flow_controls.h>
#include <apps/viewer/sort_worker.h>
#include <apps/viewer/viewer_scene.h>
#include <project/gl/gl_renderer.h>

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

namespace tr::viewer {

class VolumeView {
  public:
    // `scene` and `renderer` must outlive the view (the renderer gets the scene's mesh, scalar,
    // opaque surfaces and transfer function now). `verbose`: the flow volume prints a line per
    // grown volume (interactive mode).
    VolumeView(ViewerScene& scene, gl::GlTetRenderer& renderer, Integrator integrator,
               bool verbose);

    ViewerScene& scene() { return vs_; }
    // The flow volume's controls; null when the mesh has no 3-component point array.
    FlowControls* flow() { return flow_.get(); }
    bool flow_shown() const { return flow_ && flow_->shown(); }

    // Asks the worker for `camera`'s order when the view or the method changed; returns the
    // latest finished order (waiting only when there is none yet, or when `exact` asks for
    // this very view's).
    SortedOrder current_order(const Camera& camera, bool exact);

    // Draws the volume in `order` (frame sized as the image), or the flow volume's shown layers
    // (before the first one: the opaque surfaces alone). Records the stats for the panel.
    gl::GlFrameStats render_volume(const CameraFrame& frame, const SortedOrder& order);
    gl::GlFrameStats render_flow(const CameraFrame& frame);

    // Interactive: draws `camera`'s frame at width x height unless the last one shows the same
    // (view, order, transfer function, size, flow layers). Returns whether the view is idle:
    // its own order drawn, or every grown flow layer shown and nothing growing.
    bool draw(const Camera& camera, int width, int height);
    // Forgets the last frame: the next draw() draws.
    void invalidate() { drawn_.reset(); }

    // The renderer holding the last frame (read_image, blit_to_default, overlay).
    gl::GlTetRenderer& active() { return *active_; }

    // The transfer function: edits of scene().edit mark it dirty; rebuilt from them for the
    // current integrator (errors go to status()).
    void mark_dirty() { tf_dirty_ = true; }
    bool tf_dirty() const { return tf_dirty_; }
    void rebuild_transfer_function();

    // What the panel sets and shows.
    SortMethod method() const { return method_; }
    void set_method(SortMethod method) { method_ = method; }
    Integrator integrator() const { return integrator_; }
    void set_integrator(Integrator integrator);   // marks the transfer function dirty
    void select_scalar(const std::string& name);  // marks dirty, or says why not in status()
    const std::string& status() const { return status_; }
    double sort_ms() const { return sort_ms_; }
    bool order_current() const { return order_current_; }
    const gl::GlFrameStats& last_stats() const { return last_stats_; }

  private:
    ViewerScene& vs_;
    gl::GlTetRenderer& renderer_;
    gl::GlTetRenderer* active_ = &renderer_;
    SortWorker worker_;
    std::unique_ptr<FlowControls> flow_;
    std::optional<Camera> requested_;  // the view of the last request
    SortMethod method_, requested_method_ = SortMethod::kMpvo;
    Integrator integrator_;
    std::uint64_t view_id_ = 0, last_order_id_ = 0;
    bool order_current_ = false;
    double sort_ms_ = 0;
    bool tf_dirty_ = false;
    int tf_version_ = 0;
    std::string status_;
    gl::GlFrameStats last_stats_;
    // What the last interactive frame showed.
    struct DrawnKey {
        Camera camera;
        std::uint64_t order_id;
        int tf_version, width, height;
        std::uint64_t flow_id;
        std::size_t flow_layers;
        bool operator==(const DrawnKey& o) const;
    };
    std::optional<DrawnKey> drawn_;
};

}  // namespace tr::viewer
