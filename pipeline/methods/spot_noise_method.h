#pragma once
// The scene method `spot-noise` (issue 15; seed 4.3; flowtex/spot_noise.h): spots near a
// contour surface, advected by the flow, depth-tested against the opaque geometry and composited
// with the scene's volume at each pixel's weighted mean spot depth (pipeline/layered_volume.h).
// A render is the picture of the method's `frame`; with RenderOptions::on_frame, every frame
// 0 .. `steps` is handed over in order. The method's seed places the spots. Its keys: the table
// in spot_noise_method.cpp (docs/scene-file.md shows it).

#include <pipeline/methods/method.h>

#include <memory>

namespace tr {

std::unique_ptr<RenderMethod> make_spot_noise_method();

}  // namespace tr
