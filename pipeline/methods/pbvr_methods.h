#pragma once
// The particle-based methods (particle-based paper): `pbvr-object` (object-space particles,
// project/pbvr/pbvr_object.h) and `pbvr-image` (image-space particles, project/pbvr/pbvr_image.h).
// Both draw every volume of the scene, overlapping ones fused, over the opaque geometry.
//
// Method keys (scene.md "Method"; docs/scene-file.md lists them):
//   pbvr-object: repetitions (64), seed (1), subpixel_level (1: L x L sub-pixels per pixel),
//                sampling ("exact", "uniform", "metropolis")
//   pbvr-image:  repetitions (64), seed (1), depth ("inverse-cdf", "entry", "middle", "exit",
//                "random"), stratified (true)

#include <pipeline/methods/method.h>

#include <memory>

namespace tr {

std::unique_ptr<RenderMethod> make_pbvr_object_method();
std::unique_ptr<RenderMethod> make_pbvr_image_method();

}  // namespace tr
