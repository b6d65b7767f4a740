#pragma once
// The viewer's Dear ImGui overlay: the colour legend, the panel (array, colour map, opacity curve,
// unit distance, method, sort and integrator or the particle-based accumulation, the flow volume's
// section, timings; for a scene of several volumes one transfer-function section per volume and the
// fused modes), the seed outline and the keys window.

#include <apps/viewer/opacity_editor.h>
#include <apps/viewer/volume_view.h>
#include <core/camera.h>

#include <deque>
#include <vector>

namespace tr::viewer {

class ViewerPanel {
  public:
    // `view` must outlive the panel; the panel's edits go to it. Needs an ImGui context with
    // the GLFW and OpenGL 3 back-ends initialised.
    explicit ViewerPanel(VolumeView& view) : view_(view) {}

    // One ImGui frame, laid out for `camera` (the seed outline), drawn into the bound
    // framebuffer unless `submit` is false (layout only).
    void draw(const Camera& camera, bool submit = true);

    void toggle_panel() { show_panel_ = !show_panel_; }
    void toggle_keys() { show_keys_ = !show_keys_; }
    // The colour legend of volume 0's transfer function (apps/viewer/legend_overlay.h); on by
    // default, `--legend off` and the panel's checkbox turn it off.
    void set_legend(bool on) { show_legend_ = on; }
    // Whether an opacity point is being dragged.
    bool dragging() const;
    // A frame's time, for the panel's rolling mean over the last 30.
    void add_frame_ms(double ms);

  private:
    void draw_panel();
    // The particle-based modes: the target, what is accumulated, batch times, kept particles.
    void draw_particle_section();
    // texture-advection, spot-noise: the frame shown, how many are rendered, their times.
    void draw_animation_section();
    // A scene of several volumes: a transfer-function section per volume, the fused modes.
    void draw_fused_panel();

    VolumeView& view_;
    OpacityEditor opacity_;
    std::vector<OpacityEditor> fused_opacity_;  // one per volume of a scene of several
    std::deque<double> frame_ms_;
    bool show_panel_ = true, show_keys_ = false, show_legend_ = true;
};

}  // namespace tr::viewer
