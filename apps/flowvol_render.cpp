#include <apps/flowvol_render.h>
#include <project/cpu_renderer.h>

#include <numeric>

namespace tr::apps {

Image render_flow_volume(const FlowVolume& fv, std::size_t num_tets, const TetMesh& domain,
                         const FlowVolumeView& view) {
    const CameraFrame frame(view.camera, view.width, view.height);
    // Dye: a pale smoke colour; opacity by concentration (1 for incompressible flow), a slab
    // of a thirtieth of the domain's diagonal letting through 70%.
    const Field* concentration = find_field(fv.mesh.point_fields(), "concentration");
    std::vector<float> scalar(fv.mesh.num_points(), 1.0f);
    if (concentration) {
        for (std::size_t p = 0; p < scalar.size(); ++p) {
            scalar[p] = static_cast<float>(concentration->get(p));
        }
    }
    const TransferFunction tf =
        TransferFunction::create({{0.0, {0.85, 0.9, 1.0}}}, {{0.0, 0.0}, {1.0, 0.3}},
                                 domain.bounds().diagonal() / 30.0)
            .value();
    const SegmentShader shader(tf, Integrator::kPreintegrated, longest_edge(fv.mesh));
    std::vector<CellId> order(std::min(num_tets, fv.mesh.num_tets()));
    std::iota(order.begin(), order.end(), CellId{0});
    OpaqueLayer layer;
    RenderInputs in;
    if (!view.opaque.empty()) {
        layer = render_opaque(view.opaque, frame, view.background);
        in.opaque_color = &layer.color;
        in.opaque_depth = &layer.depth;
    }
    in.mesh = &fv.mesh;
    in.scalar = scalar;
    in.order = order;
    in.shader = &shader;
    in.camera = &frame;
    in.background = view.background;
    return render_projected_tetrahedra(in);
}

}  // namespace tr::apps
