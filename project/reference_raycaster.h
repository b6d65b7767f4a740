#pragma once
// The reference integrator: a brute-force ray caster, on a code path of its own, that the
// renderers are measured against. For each pixel ray it finds every real tet it crosses, takes
// the scalar as linear along each segment (barycentric interpolation), and integrates equation
// (2) of the texture-mapping paper with the scene's optical model by adaptive quadrature,
// segment by segment, front to back, then composites over the background.
//
// Several volumes in one space (scene.md, "Several volumes in one space") go by a path of their
// own, independent of the fused renderers it checks (project/segment_merge.h, the particle-based
// ones): per ray, every volume's segments; the ray cut at all their ends, so that on each
// interval a fixed set of volumes is present; and on each interval the summed medium (the
// extinctions add, the emissions c_i kappa_i add) integrated by the same adaptive quadrature,
// cut again where any present volume's scalar crosses a control point of its transfer function.
//
// Slow by design (O(pixels x tets per pixel) with recursive quadrature): for tests and checks.

#include <core/camera.h>
#include <core/image.h>
#include <mesh/tet_mesh.h>
#include <project/transfer_function.h>

#include <span>

namespace tr {

struct ReferenceOptions {
    double tolerance = 1e-7;  // absolute error per colour channel and per segment piece
};

// Precondition: scalar has one value per mesh point. Rays start at the eye (perspective) or
// the image plane through the camera position (orthographic): what lies behind is clipped.
Image render_reference(const TetMesh& mesh, std::span<const float> scalar,
                       const TransferFunction& tf, const CameraFrame& camera,
                       const Vec3& background, const ReferenceOptions& options = {});

// One of several volumes: its tets, the point scalar (one per mesh point), its transfer
// function. The pointers must outlive the call.
struct ReferenceVolume {
    const TetMesh* mesh = nullptr;
    std::span<const float> scalar;
    const TransferFunction* tf = nullptr;
};

// The picture of several volumes that may overlap in space, over `background` (no volume: the
// background). Same preconditions and rays as above, for each volume. With one volume it is the
// picture above to within the quadrature's tolerance (the integrals are cut and summed on
// another path), not bit for bit. Cost: as above for all volumes' tets together, plus a sort of
// each ray's segment ends.
Image render_reference(std::span<const ReferenceVolume> volumes, const CameraFrame& camera,
                       const Vec3& background, const ReferenceOptions& options = {});

// The emission-absorption integral of one ray segment of length `length` along which the
// scalar goes linearly from s0 to s1: the premultiplied colour it adds and its transparency.
struct SegmentIntegral {
    Vec3 color;
    double transparency;
};
SegmentIntegral integrate_segment(const TransferFunction& tf, double s0, double s1, double length,
                                  double tolerance);

}  // namespace tr
