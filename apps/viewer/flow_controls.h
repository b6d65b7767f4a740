#pragma once
// The viewer's flow volume: the panel's seed polygon and growth options, the grower thread,
// the grown dye on screen (one layer more each frame) with its own GL renderer, and the seed's
// outline over the picture.

#include <apps/viewer/viewer_flow.h>
#include <flowvol/point_locator.h>
#include <pipeline/flow_volume_scene.h>
#include <pipeline/pipeline.h>
#include <project/gl/gl_renderer.h>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

namespace tr::viewer {

class FlowControls {
  public:
    // `domain` and `opaque` must outlive this. `initial`: the flow volume shown at start (a
    // scene's key or the command line's); without one the panel starts from
    // default_flow_spec(domain) and nothing is shown. `verbose`: print a line per grown volume.
    FlowControls(const FlowDomain& domain, const OpaqueSet& opaque,
                 const std::optional<FlowVolumeSpec>& initial, Integrator integrator, bool verbose);

    // Whether the flow volume is shown (instead of the mesh's volume).
    bool shown() const { return shown_; }

    // Asks the grower for the panel's flow volume (a newer request replaces a pending one).
    void request();

    // Headless: grows the panel's flow volume now and puts it on screen (no layer shown yet:
    // show_layers). Returns why growth failed, if it did (nothing is on screen then).
    std::optional<Error> grow_and_wait();

    // Interactive, once a frame: puts a finished flow volume on screen, and shows one layer more
    // of the one there.
    void advance();

    // Whether the grower has work pending, running or not yet taken.
    bool busy() const { return grower_->busy(); }

    // The flow volume on screen (null before the first one).
    const GrownFlowVolume* grown() const { return flow_.get(); }
    std::size_t num_layers() const { return flow_ ? flow_->volume->layer_tets.size() : 0; }
    std::size_t layers_shown() const { return layers_shown_; }
    void show_layers(std::size_t n);  // clamped to num_layers()
    // Every grown layer is on screen (or there is none) and nothing is growing.
    bool settled() const { return !busy() && (!flow_ || layers_shown_ == num_layers()); }

    // The dye's transfer function for `integrator` (a rebuild of the volume's tables).
    void set_integrator(Integrator integrator);

    // Draws the shown layers over the opaque surfaces, in any order (one glow colour:
    // compositing commutes). Precondition: layers_shown() > 0.
    gl::GlFrameStats render(const CameraFrame& frame, const Vec3& background);
    gl::GlTetRenderer& renderer() { return *dye_renderer_; }

    // The panel's "flow volume" section (ImGui, inside a window): the seed and growth options
    // (a change regrows), what was grown and how long it took. Returns whether "show flow
    // volume" was switched.
    bool draw_section();

    // The seed polygon outlined in yellow over the picture as `camera` sees it (ImGui's
    // background draw list), when shown and the outline is on.
    void draw_seed_outline(const Camera& camera);

  private:
    void install(std::shared_ptr<GrownFlowVolume> grown);
    void set_dye_transfer_function();

    const FlowDomain& domain_;
    const OpaqueSet& opaque_;
    Integrator integrator_;
    bool verbose_;
    std::unique_ptr<FlowGrower> grower_;
    FlowVolumeSpec spec_;  // what the panel shows and a grow asks for
    bool shown_ = false, regrow_on_change_ = true, show_outline_ = true;
    std::uint64_t request_ = 0;
    std::shared_ptr<GrownFlowVolume> flow_;  // on screen
    std::optional<Error> error_;             // why the last growth failed
    std::unique_ptr<gl::GlTetRenderer> dye_renderer_;
    std::vector<CellId> dye_order_;  // 0..n-1
    std::size_t layers_shown_ = 0;
    std::unique_ptr<PointLocator> locator_;  // for the outline, made when first drawn
};

}  // namespace tr::viewer
