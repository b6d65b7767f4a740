#include <flowvol/particle_tracer.h>

#include <cmath>

namespace tr {
namespace {

bool finite(const Vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

}  // namespace

ParticleTracer::ParticleTracer(const TetMesh& mesh, const FaceAdjacency& adjacency,
                               const VelocityField& velocity)
    : velocity_(velocity), locator_(mesh, adjacency) {}

StepResult ParticleTracer::step(Particle& particle, double time, double dt) const {
    if (!particle.active) return StepResult::kLeftDomain;
    CellId hint = particle.tet;
    const Vec3 x = particle.position;
    const auto k1 = velocity_at(x, time, hint);
    if (!k1) {
        particle.active = false;
        return StepResult::kLeftDomain;
    }
    if (!finite(*k1)) {
        particle.active = false;
        return StepResult::kInvalidField;
    }
    if (glm::dot(*k1, *k1) == 0.0) {
        particle.active = false;
        return StepResult::kStalled;
    }
    CellId h2 = hint, h3 = hint, h4 = hint;
    const double half = time + 0.5 * dt;
    const auto k2 = velocity_at(x + 0.5 * dt * *k1, half, h2);
    const auto k3 = k2 ? velocity_at(x + 0.5 * dt * *k2, half, h3) : std::nullopt;
    const auto k4 = k3 ? velocity_at(x + dt * *k3, time + dt, h4) : std::nullopt;
    if (k4) {
        const Vec3 next = x + dt / 6.0 * (*k1 + 2.0 * *k2 + 2.0 * *k3 + *k4);
        if (!finite(next)) {
            particle.active = false;
            return StepResult::kInvalidField;
        }
        CellId h = h4;
        if (const auto where = locator_.locate(next, h)) {
            particle.position = next;
            particle.tet = where->tet;
            return StepResult::kMoved;
        }
    }
    // The step leaves the mesh: bisect along the Euler path for the last point inside.
    double inside = 0.0, outside = 1.0;
    CellId last = hint;
    while ((outside - inside) > 1e-9) {
        const double mid = 0.5 * (inside + outside);
        CellId h = last;
        if (const auto where = locator_.locate(x + mid * dt * *k1, h)) {
            inside = mid;
            last = where->tet;
        } else {
            outside = mid;
        }
    }
    particle.position = x + inside * dt * *k1;
    particle.tet = last;
    particle.active = false;
    return StepResult::kLeftDomain;
}

}  // namespace tr
