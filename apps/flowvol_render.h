#pragma once
// Rendering a flow volume: every tet glows the same dye colour, so the picture does not depend
// on the order the tets are composited in: no sort.

#include <core/camera.h>
#include <core/image.h>
#include <flowvol/flow_volume.h>
#include <project/opaque_geometry.h>

#include <vector>

namespace tr::apps {

struct FlowVolumeView {
    Camera camera;
    int width, height;
    Vec3 background;
    std::vector<OpaqueSurface> opaque;  // e.g. the body in the flow
};

// The first `num_tets` tets of the flow volume (the first layers), over the opaque surfaces.
Image render_flow_volume(const FlowVolume& fv, std::size_t num_tets, const TetMesh& domain,
                         const FlowVolumeView& view);

}  // namespace tr::apps
