#pragma once
// Vector types (GLM) and the few geometric predicates every module shares.

#include <glm/glm.hpp>

#include <array>
#include <limits>

namespace tr {

using Vec3 = glm::dvec3;
using Vec3f = glm::vec3;

// Axis-aligned bounds; empty when lo > hi.
struct Bounds3 {
    Vec3 lo{std::numeric_limits<double>::infinity()};
    Vec3 hi{-std::numeric_limits<double>::infinity()};

    bool empty() const { return lo.x > hi.x; }
    void extend(const Vec3& p) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    Vec3 size() const { return empty() ? Vec3(0.0) : hi - lo; }
    double diagonal() const { return empty() ? 0.0 : glm::length(hi - lo); }
};

// Six times the signed volume of tetrahedron (a, b, c, d): positive when d lies on the side
// that the normal (b - a) x (c - a) points to (VTK's convention for a tetra). A tet with
// positive orientation has orient3d > 0.
inline double orient3d(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
    return glm::dot(glm::cross(b - a, c - a), d - a);
}

// Signed volume of the tetrahedron.
inline double tet_volume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
    return orient3d(a, b, c, d) / 6.0;
}

}  // namespace tr
