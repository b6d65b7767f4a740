#pragma once
// Object-space particle-based volume rendering, O-PBVR (particle-based paper, 3.2-3.3 and 3.5):
// opaque particles generated cell by cell with a density from the transfer function, projected
// with a depth test into a buffer of sub-pixels, the pictures of many independent repetitions
// averaged in floating point.
//
// The particle model. A particle covers exactly one sub-pixel (L x L sub-pixels per pixel), so
// its cross-section is the sub-pixel's footprint where it lies: A(z) = (z p / L)^2 at depth z
// under perspective (p the pixel's size on the image plane at unit depth), (2 scale / (H L))^2
// under orthographic projection. The density that makes the chance of a particle in a slab
// of ray length dt equal to kappa dt (spec: kappa = -ln(1 - a) / unit_distance) is
//     rho(x) = kappa(s(x)) / (A(z(x)) cos theta(x)),
// theta the angle between the ray through x and the view direction: equation 12 of the paper
// with the radius taken where each particle is (not at one depth for the whole scene), so the
// expected picture is the spec's ray integral for any camera, oblique perspective included.
//
// Sampling (ObjectPbvrOptions::sampling):
// - kExact (default): a Poisson process of intensity rho in each cell, by thinning: a Poisson
//   number of candidates of the cell's largest density, uniform in the cell, each kept with
//   probability rho(x) / rho_max. The expected count is the integral of rho over the cell.
// - kUniform: the paper's basic generation (3.3.1): the cell's density taken at its centroid,
//   floor + Bernoulli many particles placed uniformly (blocky where the density varies).
// - kMetropolis: the paper's remedy: floor + Bernoulli many particles, the count from a
//   quadrature of rho over the cell, placed by a Metropolis chain whose stationary density is
//   rho inside the cell.
// Each repetition draws new particles (independent repetitions: the error falls as R^-1/2).
// Particles nearer than the near limit (perspective) or beyond opaque geometry are dropped.

#include <project/pbvr/pbvr_common.h>
#include <project/transfer_function.h>

#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

namespace tr {

enum class ParticleSampling { kExact, kUniform, kMetropolis };

std::string_view particle_sampling_name(ParticleSampling sampling);  // "exact", "uniform", ...
std::optional<ParticleSampling> parse_particle_sampling(std::string_view name);

struct ObjectPbvrOptions {
    int repetitions = 64;    // independent particle sets averaged (>= 1)
    int subpixel_level = 1;  // L: each pixel is L x L sub-pixels, one particle each (>= 1)
    std::uint64_t seed = 1;  // the same seed gives the same picture, whatever the thread count
    ParticleSampling sampling = ParticleSampling::kExact;
};

struct ObjectPbvrStats {
    std::size_t particles = 0;   // generated over all repetitions
    std::size_t candidates = 0;  // drawn before thinning (kExact)
    std::size_t projected = 0;   // that reached the picture (in view, before opaque depth)
    double generate_ms = 0;      // generating and projecting, all repetitions
    double resolve_ms = 0;       // averaging the sub-pixels and repetitions
};

// The expected number of particles in real tet `t` per repetition: the integral of rho over
// it, computed by quadrature (32 points: 8 sub-tets by midpoint subdivision, 4 points each).
// For tests and the kMetropolis count.
double expected_particles(const VolumeData& volume, CellId t, const CameraFrame& camera,
                          int subpixel_level);

// The candidate particles one repetition generates in expectation (over every volume: what
// each cell's sampling draws from), to refuse absurd work before it starts. The density grows
// as 1 / depth^2 towards a perspective eye, so a camera inside or very near the mesh can ask for
// more than any budget (kMaxObjectCandidates). Cost: O(cells).
double expected_candidates(const VolumeScene& scene, const ObjectPbvrOptions& options);

// What a view's particles are drawn from: each volume's bound on each real cell's candidates
// (the density's bound times the cell's volume, as the sampling uses it) and their sum, the
// expected candidates a repetition. Made once, it serves the budget check and the render
// (render_object_pbvr, ObjectParticleSet::generate) for the same scene, camera and options.
// Cost: O(cells).
struct ObjectPbvrPlan {
    std::vector<std::vector<float>> bounds;  // [volume][real cell]
    double candidates = 0;
};
ObjectPbvrPlan plan_object_pbvr(const VolumeScene& scene, const ObjectPbvrOptions& options);

// Candidates per repetition above this are refused (2^28: about 2,700 times those of a
// 1M-tet mesh seen whole at 512 x 512, and tens of seconds a repetition on one core).
inline constexpr double kMaxObjectCandidates = 268435456.0;

// The picture. Preconditions: the scene's sizes agree (scalar per point, opaque buffers of the
// camera's size), repetitions and subpixel_level >= 1 and their product with the pixels at
// most kMaxParticleSamples (the pipeline checks these and says so). Cost per repetition: the
// particles (the sum over cells of rho's integral, about pixels x L^2 x the optical depth of a
// ray, times the thinning overhead) plus O(pixels x L^2); memory 8 bytes per sub-pixel plus
// 24 bytes per pixel (32 with alpha).
// `plan`, when given, is plan_object_pbvr(scene, options) (not computed again).
// `alpha`, when given, is resized to width x height (row-major, row 0 at the top, as Image) and
// receives per pixel the fraction of its sub-pixels, over all repetitions, that hold a particle
// (0 where none ever does): the returned picture is then, up to float rounding, the picture the
// same call (same seed) returns over black with no opaque colour plus (1 - alpha) times the
// background or opaque colour, and that picture over black is itself an unbiased estimate of
// the premultiplied colour (premultiplied RGBA for a compositor). An opaque depth without an
// opaque colour drops the particles behind it. Asking for alpha changes no bit of the picture.
Image render_object_pbvr(const VolumeScene& scene, const ObjectPbvrOptions& options,
                         ObjectPbvrStats* stats = nullptr, const ObjectPbvrPlan* plan = nullptr,
                         std::vector<float>* alpha = nullptr);

// Particles kept between pictures (paper, 3.2: "we need to change the particle radius on the
// condition that the particle density stays the same"). Each particle keeps its position, its
// scalar and the extinction it was generated for, kappa0; rendered under a transfer function
// whose extinction there is kappa, its cross-section is scaled by f = kappa / kappa0, so that
// the density stays and the new opacity follows:
// - f <= 1 (opacity lowered): the particle is drawn with probability f (a thinning of the
//   Poisson process: exact);
// - 1 < f <= kMaxGrowth (raised): it covers the sub-pixels whose centres lie in a square of f
//   sub-pixels around it (exact in the continuum, where a particle's cross-section may be any
//   size; on the sub-pixel grid the footprint is rounded and its colour spreads up to
//   sqrt(f) / 2 sub-pixels sideways: a slight blur);
// - where kappa0 is 0 (no particles were made) or f would exceed kMaxGrowth, the particles
//   cannot give the new opacity: retarget() regenerates those cells for the new function.
// Colour changes need nothing: each particle takes the colour of its scalar when drawn.
// The particles are made for a sub-pixel footprint (their density is kappa0 / footprint): under
// orthographic projection the footprint is the same for any view direction, so a rotation reuses
// them (reusable_for); under perspective it depends on the eye: generate again.
class ObjectParticleSet {
  public:
    static constexpr double kMaxGrowth = 16.0;  // a footprint of at most 4 x 4 sub-pixels

    // The particles of every repetition for the scene's view and transfer functions (the same
    // as render_object_pbvr draws). Memory: 24 bytes a particle.
    // `plan`, when given, is plan_object_pbvr(scene, options).
    static ObjectParticleSet generate(const VolumeScene& scene, const ObjectPbvrOptions& options,
                                      const ObjectPbvrPlan* plan = nullptr);

    // Whether the kept particles hold for `camera`: orthographic, and the same sub-pixel size
    // (parallel scale, image height, sub-pixel level) as when generated; or the same camera.
    bool reusable_for(const CameraFrame& camera) const;

    // The picture for `scene` (its volumes those of generate(), its transfer functions maybe
    // new, its camera one reusable_for accepts). Cost: O(particles + sub-pixels) per repetition.
    Image render(const VolumeScene& scene, ObjectPbvrStats* stats = nullptr) const;

    // Regenerates, for the scene's transfer functions, the particles of the cells whose kept
    // particles cannot give them (see above). Returns how many cells were regenerated.
    std::size_t retarget(const VolumeScene& scene);

    std::size_t size() const;  // particles kept, all repetitions
    std::size_t byte_size() const { return size() * sizeof(Kept); }

  private:
    struct Kept {
        float x, y, z;
        float scalar;
        float kappa0;  // the extinction the particle was generated for
        std::uint32_t cell : 28;
        std::uint32_t volume : 4;
    };
    // Generates the cells marked in `only` (all when null) and appends their particles.
    void generate_cells(const VolumeScene& scene, const std::vector<std::vector<char>>* only,
                        const ObjectPbvrPlan* plan = nullptr);

    ObjectPbvrOptions options_;
    std::optional<CameraFrame> frame_;            // the view generated for
    std::vector<std::vector<Kept>> repetitions_;  // the particles of each repetition
    std::uint64_t generation_ = 0;                // bumped by retarget (new random numbers)
    // Per volume, the transfer functions cells were generated for, and per cell which one.
    std::vector<std::vector<TransferFunction>> functions_;
    std::vector<std::vector<std::uint16_t>> cell_function_;
};

}  // namespace tr
