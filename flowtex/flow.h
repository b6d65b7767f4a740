#pragma once
// The velocity texture advection follows: a field on a TetMesh (flowvol's locator and velocity)
// or an analytic flow (tests, benchmarks), with RK4 steps forward or backward in time.

#include <core/math.h>
#include <flowvol/particle_tracer.h>
#include <flowvol/velocity_field.h>

#include <functional>
#include <optional>

namespace tr {

class Flow {
  public:
    virtual ~Flow() = default;
    // The velocity at p at `time`, or nothing where the flow is not defined (outside the mesh).
    // `hint` is a cell near p (kNoCell: none) and is updated; analytic flows ignore it.
    virtual std::optional<Vec3> at(const Vec3& p, double time, CellId& hint) const = 0;
    // True when the velocity does not depend on time.
    virtual bool steady() const = 0;
};

// A VelocityField on a TetMesh: point location by flowvol's adjacency walk. `mesh`, `adjacency`
// and `velocity` must outlive it. Cost: flowvol's PointLocator build.
class MeshFlow final : public Flow {
  public:
    MeshFlow(const TetMesh& mesh, const FaceAdjacency& adjacency, const VelocityField& velocity)
        : tracer_(mesh, adjacency, velocity), steady_(velocity.is_steady()) {}
    std::optional<Vec3> at(const Vec3& p, double time, CellId& hint) const override {
        return tracer_.velocity_at(p, time, hint);
    }
    bool steady() const override { return steady_; }
    const PointLocator& locator() const { return tracer_.locator(); }
    const VelocityField& velocity() const { return tracer_.velocity(); }

  private:
    ParticleTracer tracer_;
    bool steady_;
};

// v(p, t) from a function, defined inside `domain` (inclusive; default everywhere).
class AnalyticFlow final : public Flow {
  public:
    AnalyticFlow(std::function<Vec3(const Vec3&, double)> velocity, bool steady,
                 Bounds3 domain = Bounds3{Vec3(-1e300), Vec3(1e300)})
        : velocity_(std::move(velocity)), steady_(steady), domain_(domain) {}
    std::optional<Vec3> at(const Vec3& p, double time, CellId& hint) const override;
    bool steady() const override { return steady_; }

  private:
    std::function<Vec3(const Vec3&, double)> velocity_;
    bool steady_;
    Bounds3 domain_;
};

// v = velocity everywhere.
AnalyticFlow uniform_flow(const Vec3& velocity);
// Rigid rotation about the z axis through `centre`, angular speed omega (radians per unit time,
// counter-clockwise seen from +z): v = omega * (-(y - cy), x - cx, 0).
AnalyticFlow rigid_rotation(const Vec3& centre, double omega);
// The double gyre (Shadden, Lekien and Marsden 2005) on [0, 2] x [0, 1] (z ignored, v_z = 0):
// u = -pi A sin(pi f) cos(pi y), v = pi A cos(pi f) sin(pi y) df/dx, f = a x^2 + b x,
// a = eps sin(w t), b = 1 - 2 eps sin(w t). Defined everywhere (tangent to the box's sides).
AnalyticFlow double_gyre(double amplitude = 0.1, double epsilon = 0.25,
                         double omega = 2.0 * 3.14159265358979323846 / 10.0);

// One classical RK4 step of x' = P(v(x, t)) from `time` to time + dt (dt may be negative: a
// backward trace), where P removes the component along `normal` (a unit vector, or zero for
// none) so that a trace stays in the sheet's plane. Nothing when any stage leaves the flow's
// domain, or, with `check_end`, when the end point does. Cost: four velocity lookups (five with
// check_end).
std::optional<Vec3> rk4_step(const Flow& flow, const Vec3& x, double time, double dt,
                             const Vec3& normal, CellId& hint, bool check_end = true);
// The same with the first stage's velocity v(x, time) given (a caller that kept it from the
// step before): three lookups (four with check_end), the same result.
std::optional<Vec3> rk4_step_from(const Flow& flow, const Vec3& x, const Vec3& velocity,
                                  double time, double dt, const Vec3& normal, CellId& hint,
                                  bool check_end = true);

}  // namespace tr
