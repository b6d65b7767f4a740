#pragma once
// The projected-tetrahedra method (texture-mapping paper, 3.2; the default): the volume's tets
// composited back to front in a visibility order over the opaque geometry, each pixel's
// segment integrated by the chosen integrator; or, for a scene with a flow volume, the dye's
// tets (one colour: no sort); or, with RenderOptions::reference, the brute-force reference ray
// caster.

#include <pipeline/methods/method.h>

#include <memory>

namespace tr {

std::unique_ptr<RenderMethod> make_projected_tetrahedra_method();

}  // namespace tr
