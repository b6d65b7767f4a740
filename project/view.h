#pragma once
// How a picture is seen and what lies behind what is drawn: the one description every renderer's
// inputs share (projected tetrahedra, PBVR and the fused volumes, splats, vector splats, spots).

#include <core/camera.h>
#include <core/image.h>
#include <core/math.h>

#include <vector>

namespace tr {

struct View {
    // The picture: camera.width() x camera.height() pixels. Required.
    const CameraFrame* camera = nullptr;
    // What lies behind: the background colour, or opaque geometry already drawn
    // (project/opaque_geometry.h): its colour per pixel and, per pixel, the ray parameter of its
    // nearest surface (+inf where there is none), which stops every ray. Either may be null:
    // then the background, and rays that run on. When given, of the camera's size.
    Vec3 background{0.0};
    const Image* opaque_color = nullptr;
    const std::vector<double>* opaque_depth = nullptr;
};

}  // namespace tr
