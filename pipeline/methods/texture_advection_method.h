#pragma once
// The scene method `texture-advection` (issue 15; seed 4.4; flowtex/advected_sheets.h): several
// semi-transparent advected sheets drawn with the scene's volume (projected tetrahedra with its
// transfer function) and opaque geometry, composited in depth order
// (pipeline/layered_volume.h). A render is the picture of the method's `frame`; with
// RenderOptions::on_frame, every frame 0 .. `steps` is handed over in order. Its keys: the
// table in texture_advection_method.cpp (docs/scene-file.md shows it).

#include <pipeline/methods/method.h>

#include <memory>

namespace tr {

std::unique_ptr<RenderMethod> make_texture_advection_method();

}  // namespace tr
