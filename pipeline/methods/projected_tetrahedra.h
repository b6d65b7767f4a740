#pragma once
// The projected-tetrahedra method (texture-mapping paper, 3.2; the default): the volume's tets
// composited back to front in a visibility order over the opaque geometry, each pixel's
// segment integrated by the chosen integrator; or, for a scene with a flow volume, the dye's
// tets (one colour: no sort); or, with RenderOptions::reference, the brute-force reference ray
// caster.

#include <pipeline/methods/method.h>
#include <project/opaque_geometry.h>

#include <memory>

namespace tr {

std::unique_ptr<RenderMethod> make_projected_tetrahedra_method();

// The scene's volumes (no flow volume; RenderOptions::reference is not looked at) as the method
// draws them: one volume in its visibility order, several (or one without an exact order) by
// the segment merge. With `stops`, over that layer (colour and per-pixel ray parameter, of the
// picture's size) instead of the scene's opaque surfaces: how the animated methods split the
// volume's ray integral at their sheets' depths (pipeline/layered_volume.h).
Result<RenderResult> render_projected_volume(Pipeline& pipeline, const Scene& scene,
                                             const RenderOptions& options,
                                             const OpaqueLayer* stops = nullptr);

}  // namespace tr
