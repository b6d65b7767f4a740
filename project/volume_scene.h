#pragma once
// What the renderers that draw several volumes at once take (particle-based rendering, the
// exact segment merge): the volumes — each a tet mesh with its point scalar and transfer
// function — and how they are seen, over a background or opaque geometry already drawn.

#include <core/camera.h>
#include <core/image.h>
#include <mesh/tet_mesh.h>
#include <project/segment_shader.h>
#include <project/transfer_function.h>

#include <span>
#include <vector>

namespace tr {

// One volume: its tets, the point scalar (one per mesh point) and its transfer function, and
// optionally a shader of that transfer function (project/segment_shader.h) for what a renderer
// integrates over one segment of one volume (a segment's colour and opacity, its mean colour).
struct VolumeData {
    const TetMesh* mesh = nullptr;
    std::span<const float> scalar;
    const TransferFunction* tf = nullptr;
    const SegmentShader* shader = nullptr;
};

// What is drawn and how it is seen. Several volumes may overlap in space (fused rendering: the
// spec's optical model adds their extinctions and emissions where they overlap).
struct VolumeScene {
    std::vector<VolumeData> volumes;
    const CameraFrame* camera = nullptr;
    Vec3 background{0.0};
    // Opaque geometry already drawn (project/opaque_geometry.h): colour per pixel and the ray
    // parameter of the surface per pixel (+inf where none). Either may be null.
    const Image* opaque_color = nullptr;
    const std::vector<double>* opaque_depth = nullptr;
};

}  // namespace tr
