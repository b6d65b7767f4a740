#pragma once
// The animated flow-texture methods of scene files (issue 15; flowtex/): `texture-advection`
// (seed 4.4: several semi-transparent advected sheets) and `spot-noise` (seed 4.3: spots near a
// contour surface). Either draws the scene's volume (projected tetrahedra with its transfer
// function) and opaque geometry with the textured sheets or the spots composited in depth order
// (pipeline/layered_volume.h). A render is the picture of the method's `frame`; with
// RenderOptions::on_frame, every frame 0 .. `steps` is handed over in order.
//
// texture-advection keys (docs/scene-file.md): vectors (required: a 3-component point array of
// volume 0's mesh), slices ([[px, py, pz, nx, ny, nz], ...], 1 to 16 sheets; default one
// through the mesh bounds' centre normal to their thinnest axis), steps (100), frame (steps),
// dt (> 0; default as `tetrender advect`), unsteady (false), start_time, advection ("backward",
// "forward"), reinject (even, 40; 0 off), resolution (256), sheet_opacity (0.6, in (0, 1]).
// spot-noise keys: vectors (required), scalar (a 1-component point array; default the scene's
// scalar), iso (required, inside the scalar's range), band, count (20000), dt, steps (100),
// frame (steps), lifetime, unsteady, start_time, spot_opacity (1.5: W's opacity rate); the
// method's seed places the spots.

#include <pipeline/method.h>

#include <memory>

namespace tr {

std::unique_ptr<RenderMethod> make_texture_advection_method();
std::unique_ptr<RenderMethod> make_spot_noise_method();

}  // namespace tr
