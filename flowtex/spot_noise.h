#pragma once
// Spot noise near a contour surface (seed section 4.3; van Wijk 1991): particles in a thin band
// around the surface s(x) = iso of a point scalar, advected by a flow frame after frame, each
// drawn as a Gaussian spot stretched into an ellipse along its projected velocity.
//
// The band: the points x of the mesh with |s(x) - iso| < band |grad s| in the tet holding x,
// s linear in each tet, i.e. within `band` world units of the surface to first order. A band in
// world units keeps an even thickness where the scalar's gradient varies (a band in scalar
// units would be thick where the scalar is flat and vanish where it is steep), so spots seeded
// uniformly by volume lie evenly over the surface. Tets where s is constant are not in it.
//
// Seeding: uniformly by volume in the band, by rejection: a tet drawn among those whose scalar
// range meets the band with probability proportional to its volume, a uniform point in it,
// kept when it is in the band and the flow is defined there.
//
// Advection: each frame, one classical RK4 step of dt per spot (flowtex/flow.h). A spot that
// leaves the flow's domain or the band, or whose age reaches `lifetime_frames` (ages start
// staggered, so about count / lifetime spots a frame), is reseeded, so the count in the band is
// always `count`. Reseeding keeps the density even: a grid of cubes over the band (about 64
// spots a cube) holds each cube's target, count x the cube's share of the band's volume
// (estimated from max(16 count, 2^18) uniform samples, at most 2^22, when created); the spots
// to reseed go to the cubes with the largest deficits (target minus the spots now in them;
// water-filling: each cube above a common level L gets its deficit less L, the rest spread
// evenly over the cubes at L) and are placed uniformly by volume in the band within their
// cube (by rejection from the band tets meeting it, or from the cube itself where those tets
// are more than twice its volume). Spots converging somewhere (compressible flow) are thinned there
// by the lifetime: those dying in a cube over its target are placed elsewhere. Each spot draws its
// random numbers from (seed, spot index, generation): the same seed gives the same spots
// whatever the thread count.

#include <core/result.h>
#include <flowtex/flow.h>
#include <flowvol/point_locator.h>
#include <mesh/field.h>
#include <mesh/tet_mesh.h>

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace tr {

namespace detail {
class SpotRandom;
}

struct SpotNoiseOptions {
    double iso = 0;             // the contour value (inside the scalar's range)
    double band = 0;            // half-width in world units (> 0)
    std::size_t count = 10000;  // spots, 1 .. kMaxSpots
    double dt = 0.05;           // flow time per frame (> 0)
    double start_time = 0;      // the time of frame 0 (unsteady flows)
    int lifetime_frames = 60;   // a spot is reseeded at this age; 0: never for age
    std::uint64_t seed = 0x5b07;
};

// About 70 bytes a spot: 10^7 spots take 0.7 GB.
inline constexpr std::size_t kMaxSpots = 10'000'000;

class SpotNoise {
  public:
    // Seeds `count` spots (frame 0). `mesh`, `locator` (over mesh), `scalar` (1 component, a
    // point field of mesh) and `flow` must outlive it. Errors (kInvalidArgument, one line): iso
    // outside the scalar's range (the message gives the range), a scalar field that is not one
    // component a point, count 0 or above kMaxSpots, band or dt not positive and finite, a band
    // that holds no tet, a spot that found no point of the band with a defined flow in 10000
    // tries. Error::about names the option: "scalar", "count", "band" or "iso". Cost: O(tets) to
    // find the band's tets, rejection sampling per spot, and 16 x count samples (2^18 .. 2^22) for
    // the reseeding grid's targets.
    static Result<SpotNoise> create(const TetMesh& mesh, const PointLocator& locator,
                                    const Field& scalar, const Flow& flow,
                                    const SpotNoiseOptions& options);

    // To the next frame (time + dt): an RK4 step per spot, those out reseeded. Cost: four
    // velocity lookups (the first stage's is the last frame's end-point lookup, kept in
    // velocities()) and a point location per spot, parallel over spots.
    void advance();

    int frame() const { return frame_; }
    double time() const { return options_.start_time + frame_ * options_.dt; }
    std::size_t size() const { return positions_.size(); }
    std::span<const Vec3> positions() const { return positions_; }
    // The flow's velocity at each spot at time().
    std::span<const Vec3> velocities() const { return velocities_; }
    // How many times each spot has been reseeded (a spot whose generation did not change
    // between two frames was moved by the flow).
    std::span<const std::uint32_t> generations() const { return generations_; }
    // Spots reseeded by the last advance().
    std::size_t reseeded() const { return reseeded_; }
    std::size_t band_tets() const { return band_tets_.size(); }
    double band() const { return options_.band; }
    double dt() const { return options_.dt; }
    // The mean speed |v| over the spots now.
    double mean_speed() const;
    // From the next advance on: dt (> 0) and the lifetime (>= 0); the spots stay.
    void retime(double dt, int lifetime_frames);

    // |s(p) - iso| / |grad s| in the tet holding p (world units; 0 on the surface, +inf in a
    // tet where s is constant and not iso), or nothing outside the mesh. `hint`: a tet near p.
    std::optional<double> distance_to_surface(const Vec3& p, CellId& hint) const;
    // The same at a location in mesh.
    double distance_at(const Location& location) const;

  private:
    SpotNoise(const TetMesh& mesh, const PointLocator& locator, const Field& scalar,
              const Flow& flow, const SpotNoiseOptions& options)
        : mesh_(&mesh), locator_(&locator), scalar_(&scalar), flow_(&flow), options_(options) {}
    // A fresh spot i (its generation already bumped) at time t, anywhere in the band or (cell
    // >= 0) in that cube of the grid; false when no try succeeded.
    bool seed_spot(std::size_t i, double t, int cell = -1);
    void build_grid();
    // A uniform point in band tet `cell` (or one drawn by volume when kNoCell) and whether it
    // lies in the band (the scalar from its barycentric weights in that tet).
    struct BandSample {
        Vec3 point{0.0};
        CellId tet = kNoCell;
        bool in_band = false;
    };
    BandSample sample_band_tet(detail::SpotRandom& random, CellId cell = kNoCell) const;
    int cell_of(const Vec3& p) const;

    const TetMesh* mesh_;
    const PointLocator* locator_;
    const Field* scalar_;
    const Flow* flow_;
    SpotNoiseOptions options_;
    std::vector<double> gradient_norm_;  // |grad s| per tet
    std::vector<CellId> band_tets_;
    std::vector<double> band_cdf_;  // cumulative volumes of band_tets_, normalised to 1
    int frame_ = 0;
    std::vector<Vec3> positions_, velocities_;
    std::vector<CellId> hints_, flow_hints_;
    // The flow's velocity when the flow is a MeshFlow on mesh_ (its tets are mesh_'s: one point
    // location serves the velocity and the band test), else null.
    const VelocityField* shared_velocity_ = nullptr;
    std::vector<std::uint32_t> generations_;
    std::vector<int> ages_;
    std::vector<std::uint8_t> flags_;  // per spot: seeded (create), to reseed (advance)
    std::vector<int> cells_;           // per spot moved by advance(): its reseeding cube
    // The reseeding grid: n^3 cubes of side cell_size_ from grid_lo_; per cube the band tets
    // meeting it (CSR, with cumulative volumes normalised per cube) and its target.
    Vec3 grid_lo_{0.0};
    double cell_size_ = 1;
    int grid_n_ = 1;
    std::vector<std::uint32_t> cell_start_;
    std::vector<CellId> cell_tets_;
    std::vector<double> cell_cdf_;
    std::vector<std::uint8_t> box_sampling_;  // per cube: draw from the cube, not its tets
    std::vector<double> target_;  // expected spots per cube: count x its share of the band
    std::vector<std::uint32_t> target_cells_;  // the cubes whose target is above 0, in order
    std::vector<int> reseed_cells_;
    std::size_t reseeded_ = 0;
};

}  // namespace tr
