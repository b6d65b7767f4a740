#pragma once
// Particles advected through a velocity field (steady or unsteady) on a TetMesh by classical
// RK4, with point location by adjacency walks: the engine of flow volumes (texture-mapping
// paper, 4.1).

#include <flowvol/point_locator.h>
#include <flowvol/velocity_field.h>

#include <optional>

namespace tr {

struct Particle {
    Vec3 position;
    CellId tet = kNoCell;  // the tet holding `position` (a hint for the next step)
    bool active = true;    // false once it left the domain, stalled or met a bad value
};

enum class StepResult {
    kMoved,         // a full step inside the domain
    kLeftDomain,    // the step would leave the mesh: the particle stops on the boundary
    kStalled,       // zero velocity: it cannot move
    kInvalidField,  // NaN or Inf in the field where it is
};

class ParticleTracer {
  public:
    // `velocity` is defined on `mesh`. All three must outlive the tracer.
    ParticleTracer(const TetMesh& mesh, const FaceAdjacency& adjacency,
                   const VelocityField& velocity);

    // The velocity at p at `time`, or nothing outside the mesh; `hint` is updated to the tet
    // found.
    std::optional<Vec3> velocity_at(const Vec3& p, double time, CellId& hint) const {
        const auto where = locator_.locate(p, hint);
        if (!where) return std::nullopt;
        hint = where->tet;
        return velocity_.at(*where, time);
    }

    // One RK4 step from `time` to time + dt (dt > 0). A step that would leave the mesh is cut where
    // the particle's path crosses the boundary (bisection on the Euler path, to 1e-9 of dt) and the
    // particle stops there. Inactive particles are left alone (kLeftDomain is returned).
    StepResult step(Particle& particle, double time, double dt) const;

    const PointLocator& locator() const { return locator_; }
    const VelocityField& velocity() const { return velocity_; }

  private:
    const VelocityField& velocity_;
    PointLocator locator_;
};

}  // namespace tr
