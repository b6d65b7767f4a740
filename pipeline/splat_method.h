#pragma once
// The `splat` method (texture-mapping paper, 3.1; project/splat_renderer.h): the points of the
// scene's mesh — a regular grid's lattice, or any mesh's points — each spread by a
// reconstruction kernel and composited back to front, over the opaque geometry. One volume.
//
// Method keys (docs/scene-file.md): kernel ("crawfis-max", the paper's cubic, default;
// "gaussian"), spacing (the lattice spacing h the kernel is scaled to, > 0; default: that of a
// lattice filling the points' bounds, project/splat_renderer.h lattice_spacing, exact for a
// regular grid with the same spacing on every axis).

#include <memory>
#include <pipeline/method.h>

namespace tr {

std::unique_ptr<RenderMethod> make_splat_method();

}  // namespace tr
