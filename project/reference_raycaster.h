#pragma once
// The reference integrator: a brute-force ray caster, on a code path of its own, that the
// renderers are measured against. For each pixel ray it finds every real tet it crosses, takes
// the scalar as linear along each segment (barycentric interpolation), and integrates equation
// (2) of the texture-mapping paper with the scene's optical model by adaptive quadrature,
// segment by segment, front to back, then composites over the background.
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

// The emission-absorption integral of one ray segment of length `length` along which the
// scalar goes linearly from s0 to s1: the premultiplied colour it adds and its transparency.
struct SegmentIntegral {
    Vec3 color;
    double transparency;
};
SegmentIntegral integrate_segment(const TransferFunction& tf, double s0, double s1, double length,
                                  double tolerance);

}  // namespace tr
