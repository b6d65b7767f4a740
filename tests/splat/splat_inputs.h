#pragma once
// The splat renderer's inputs for a lattice the tests draw: its points and scalar, spacing,
// transfer function, footprint, camera and compositing (the rest defaulted). The referenced
// objects must outlive the inputs.
#include <project/splat/splat_renderer.h>

#include <span>

namespace tr::testing {

inline SplatInputs splat_inputs(std::span<const Vec3> points, std::span<const float> scalar,
                                double spacing, const TransferFunction& tf,
                                const SplatFootprint& footprint, const CameraFrame& camera,
                                SplatCompositing compositing) {
    SplatInputs in;
    in.points = points;
    in.scalar = scalar;
    in.spacing = spacing;
    in.tf = &tf;
    in.footprint = &footprint;
    in.camera = &camera;
    in.compositing = compositing;
    return in;
}

}  // namespace tr::testing
