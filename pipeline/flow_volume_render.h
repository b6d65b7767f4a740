#pragma once
// Rendering a flow volume: every tet glows the same dye colour, so the picture does not depend
// on the order the tets are composited in: no sort.

#include <core/camera.h>
#include <core/image.h>
#include <flowvol/flow_volume.h>
#include <pipeline/scene.h>
#include <project/opaque_geometry.h>
#include <project/segment_shader.h>
#include <project/transfer_function.h>

#include <vector>

namespace tr {

struct FlowVolumeView {
    Camera camera;
    int width, height;
    Vec3 background;
    std::vector<OpaqueSurface> opaque;  // e.g. the body in the flow
    // The dye's colour, opacity and unit distance (the rest of the spec is not used here):
    // flow_volume_scene.h dye_transfer_function.
    FlowVolumeSpec dye;
    // The domain's boundary as a faint veil in front of the dye (its nearest surface, shaded,
    // at 15% over the picture): context for where the flow is.
    const SurfaceMesh* context = nullptr;
};

// Renders a flow volume layer after layer: since every tet has the same colour, compositing
// is order independent, so each frame is the previous one with only the new layer's tets
// composited over it.
class FlowVolumeRenderer {
  public:
    FlowVolumeRenderer(const FlowVolume& fv, const TetMesh& domain, const FlowVolumeView& view);

    // The picture with tets [0, end) drawn; `end` must not decrease from call to call. Only
    // the tets added since the last call are drawn.
    Image render_up_to(std::size_t end);

  private:
    void draw_up_to(std::size_t end);

    const FlowVolume& fv_;
    CameraFrame frame_;
    TransferFunction tf_;
    SegmentShader shader_;
    std::vector<float> scalar_;
    OpaqueLayer opaque_;
    bool has_opaque_ = false;
    OpaqueLayer veil_;
    bool has_veil_ = false;
    Image image_;
    std::size_t drawn_ = 0;
};

}  // namespace tr
