#pragma once
// Semi-transparent surfaces (advected sheets, a layer of spots) composited in depth order with a
// scene's volume and opaque geometry. The volume's ray integral is split at the surfaces' depths
// by rendering it (projected tetrahedra) with each surface as an opaque stop: for the k-th
// nearest surface fragment of a pixel at ray parameter d_k, one render gives F_k = the volume's
// light from the eye to d_k and another its transmittance T_k (the stop black, then white).
// With fragment k of colour c_k and opacity a_k (nearest first):
//
//   picture = sum_k w_k (F_k + T_k c_k) + w_inf R,   w_k = a_k prod_{j<k} (1 - a_j),
//   w_inf = prod_k (1 - a_k),
//
// R the volume over the scene's opaque geometry: the emission-absorption integral with each
// surface a thin layer of opacity a_k, exactly (the volume's light from the eye to depth d is
// linear in what lies behind d; a ray stops at fragment k with weight w_k, or passes them all).
// Fragments at or behind the opaque geometry's depth are hidden.
// Cost: 2K + 1 volume renders for K fragments per pixel at most (once; the surfaces' colours
// and opacities may change from frame to frame at the cost of one pass over the pixels).

#include <core/camera.h>
#include <core/image.h>
#include <core/result.h>
#include <pipeline/pipeline.h>
#include <pipeline/scene.h>
#include <project/opaque_geometry.h>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace tr {

// One surface's fragments in a picture: per pixel (row 0 at the top) its colour and opacity
// (0: no fragment there).
struct SurfaceFragments {
    std::vector<Vec3f> color;
    std::vector<float> alpha;
};

class LayeredVolume {
  public:
    // The volume of `scene` (its volumes, transfer functions, opaque geometry, camera, size and
    // background; its method is not looked at: projected tetrahedra with `options`' sort and
    // integrator) prepared under surfaces whose per-pixel ray parameters are `depths[s]`
    // (the camera's pixel rays; +inf or <= 0 where surface s does not cross the ray in front of
    // the eye). Errors: the pipeline's; layers whose pictures would not fit the memory budget
    // (core/memory_budget.h, 34 bytes a pixel and surface). Stats: volume_renders, volume_ms,
    // layers (K).
    // With `volume_drawn` false (a 2D flow's scene: its mesh has no volume) nothing is rendered
    // and the surfaces lie over the opaque geometry and background alone (F_k = 0, T_k = 1,
    // R = the opaque layer): volume_renders 0.
    static Result<LayeredVolume> create(Pipeline& pipeline, const Scene& scene,
                                        const RenderOptions& options,
                                        std::span<const std::vector<double>> depths,
                                        NamedStats& stats, std::vector<std::string>& notes,
                                        bool volume_drawn = true);

    // The picture with surface s drawn as `surfaces[s]` (same count and order as the depths).
    // Bit-identical whatever the thread count.
    Image composite(std::span<const SurfaceFragments> surfaces) const;

    // The scene's opaque geometry (empty when it has none).
    const OpaqueLayer& opaque() const { return opaque_; }
    int layers() const { return static_cast<int>(rank_.size()); }

  private:
    int width_ = 0, height_ = 0;
    OpaqueLayer opaque_;
    std::vector<std::vector<std::int8_t>> rank_;  // per rank k, per pixel: the surface, or -1
    std::vector<Image> front_, transmittance_;    // per rank: F_k, T_k
    Image full_;                                  // R
};

// Whether the pictures and depths of `surfaces` layers over the scene's picture fit the memory
// budget (core/memory_budget.h; about 34 bytes a pixel and surface): an error naming the scene
// file otherwise. LayeredVolume::create checks it; callers check it before making the depths.
Status check_layers_memory(const Scene& scene, std::size_t surfaces);

// Per pixel (row 0 at the top), the ray parameter at which `frame`'s pixel ray crosses the plane
// through `point` with normal `normal`; +inf where it does not in front of the eye (parallel, or
// behind). The depth opaque geometry and the volume renderer use.
std::vector<double> plane_depths(const CameraFrame& frame, const Vec3& point, const Vec3& normal);

}  // namespace tr
