#include <pipeline/flow_volume_render.h>
#include <pipeline/flow_volume_scene.h>
#include <project/cpu_renderer.h>

#include <cmath>
#include <numeric>

namespace tr {
namespace {

constexpr double kVeilOpacity = 0.15;

}  // namespace

FlowVolumeRenderer::FlowVolumeRenderer(const FlowVolume& fv, const TetMesh& domain,
                                       const FlowVolumeView& view)
    : fv_(fv),
      frame_(view.camera, view.width, view.height),
      tf_(dye_transfer_function(view.dye, domain)),
      shader_(tf_, Integrator::kPreintegrated, longest_edge(fv.mesh)),
      scalar_(fv.mesh.num_points(), 1.0f),
      image_(view.width, view.height, Vec3f(view.background)) {
    if (const Field* c = find_field(fv.mesh.point_fields(), "concentration")) {
        for (std::size_t p = 0; p < scalar_.size(); ++p) scalar_[p] = static_cast<float>(c->get(p));
    }
    if (!view.opaque.empty()) {
        opaque_ = render_opaque(view.opaque, frame_, view.background);
        image_ = opaque_.color;
        has_opaque_ = true;
    }
    if (view.context) {
        veil_ = render_opaque({{view.context, Vec3(0.7, 0.72, 0.8)}}, frame_, Vec3(0.0));
        has_veil_ = true;
    }
}

Image FlowVolumeRenderer::render_up_to(std::size_t end) {
    end = std::min(end, fv_.mesh.num_tets());
    if (end > drawn_) draw_up_to(end);
    if (!has_veil_) return image_;
    Image veiled = image_;
    for (int y = 0; y < veiled.height; ++y) {
        for (int x = 0; x < veiled.width; ++x) {
            const std::size_t p = static_cast<std::size_t>(y) * veiled.width + x;
            if (!std::isfinite(veil_.depth[p])) continue;
            veiled.at(x, y) = static_cast<float>(1 - kVeilOpacity) * veiled.at(x, y) +
                              static_cast<float>(kVeilOpacity) * veil_.color.at(x, y);
        }
    }
    return veiled;
}

void FlowVolumeRenderer::draw_up_to(std::size_t end) {
    std::vector<CellId> order(end - drawn_);
    std::iota(order.begin(), order.end(), static_cast<CellId>(drawn_));
    RenderInputs in;
    in.mesh = &fv_.mesh;
    in.scalar = scalar_;
    in.order = order;
    in.shader = &shader_;
    in.camera = &frame_;
    in.opaque_color = &image_;  // the picture so far
    if (has_opaque_) in.opaque_depth = &opaque_.depth;
    image_ = render_projected_tetrahedra(in);
    drawn_ = end;
}

}  // namespace tr
