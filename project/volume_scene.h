#pragma once
// What the renderers that draw several volumes at once take (particle-based rendering, the
// exact segment merge): the volumes — each a tet mesh with its point scalar and transfer
// function — and how they are seen, over a background or opaque geometry already drawn.

#include <core/camera.h>
#include <core/image.h>
#include <mesh/tet_mesh.h>
#include <project/segment_shader.h>
#include <project/transfer_function.h>
#include <project/view.h>

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

// What is drawn, in a view (camera, background, opaque layer: project/view.h). Several volumes
// may overlap in space (fused rendering: the spec's optical model adds their extinctions and
// emissions where they overlap).
struct VolumeScene : View {
    std::vector<VolumeData> volumes;
};

}  // namespace tr
