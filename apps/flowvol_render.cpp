#include <apps/flowvol_render.h>
#include <project/cpu_renderer.h>

#include <numeric>

namespace tr::apps {
namespace {

// Dye: a pale smoke colour; opacity by concentration (1 for incompressible flow), a slab of a
// thirtieth of the domain's diagonal letting through 70%.
TransferFunction dye(const TetMesh& domain) {
    return TransferFunction::create({{0.0, {0.85, 0.9, 1.0}}}, {{0.0, 0.0}, {1.0, 0.3}},
                                    domain.bounds().diagonal() / 30.0)
        .value();
}

}  // namespace

FlowVolumeRenderer::FlowVolumeRenderer(const FlowVolume& fv, const TetMesh& domain,
                                       const FlowVolumeView& view)
    : fv_(fv),
      frame_(view.camera, view.width, view.height),
      tf_(dye(domain)),
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
}

const Image& FlowVolumeRenderer::render_up_to(std::size_t end) {
    end = std::min(end, fv_.mesh.num_tets());
    if (end <= drawn_) return image_;
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
    return image_;
}

}  // namespace tr::apps
