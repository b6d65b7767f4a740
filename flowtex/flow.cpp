#include <flowtex/flow.h>

#include <cmath>

namespace tr {

std::optional<Vec3> AnalyticFlow::at(const Vec3& p, double time, CellId& /*hint*/) const {
    if (p.x < domain_.lo.x || p.y < domain_.lo.y || p.z < domain_.lo.z || p.x > domain_.hi.x ||
        p.y > domain_.hi.y || p.z > domain_.hi.z) {
        return std::nullopt;
    }
    return velocity_(p, time);
}

AnalyticFlow uniform_flow(const Vec3& velocity) {
    return AnalyticFlow([velocity](const Vec3&, double) { return velocity; }, true);
}

AnalyticFlow rigid_rotation(const Vec3& centre, double omega) {
    return AnalyticFlow(
        [centre, omega](const Vec3& p, double) {
            return Vec3(-omega * (p.y - centre.y), omega * (p.x - centre.x), 0.0);
        },
        true);
}

AnalyticFlow double_gyre(double amplitude, double epsilon, double omega) {
    return AnalyticFlow(
        [amplitude, epsilon, omega](const Vec3& p, double t) {
            constexpr double kPi = 3.14159265358979323846;
            const double s = epsilon * std::sin(omega * t);
            const double a = s, b = 1.0 - 2.0 * s;
            const double f = a * p.x * p.x + b * p.x;
            const double dfdx = 2.0 * a * p.x + b;
            return Vec3(-kPi * amplitude * std::sin(kPi * f) * std::cos(kPi * p.y),
                        kPi * amplitude * std::cos(kPi * f) * std::sin(kPi * p.y) * dfdx, 0.0);
        },
        false);
}

std::optional<Vec3> rk4_step(const Flow& flow, const Vec3& x, double time, double dt,
                             const Vec3& normal, CellId& hint, bool check_end) {
    const auto k1 = flow.at(x, time, hint);
    if (!k1) return std::nullopt;
    return rk4_step_from(flow, x, *k1, time, dt, normal, hint, check_end);
}

std::optional<Vec3> rk4_step_from(const Flow& flow, const Vec3& x, const Vec3& velocity,
                                  double time, double dt, const Vec3& normal, CellId& hint,
                                  bool check_end) {
    auto tangent = [&](const Vec3& v) { return v - glm::dot(v, normal) * normal; };
    const Vec3 v1 = tangent(velocity);
    CellId h = hint;
    const double half = time + 0.5 * dt;
    const auto k2 = flow.at(x + 0.5 * dt * v1, half, h);
    if (!k2) return std::nullopt;
    const Vec3 v2 = tangent(*k2);
    const auto k3 = flow.at(x + 0.5 * dt * v2, half, h);
    if (!k3) return std::nullopt;
    const Vec3 v3 = tangent(*k3);
    const auto k4 = flow.at(x + dt * v3, time + dt, h);
    if (!k4) return std::nullopt;
    const Vec3 next = x + dt / 6.0 * (v1 + 2.0 * v2 + 2.0 * v3 + tangent(*k4));
    if (!std::isfinite(next.x) || !std::isfinite(next.y) || !std::isfinite(next.z)) {
        return std::nullopt;
    }
    if (check_end) {
        CellId end_hint = h;
        if (!flow.at(next, time + dt, end_hint)) return std::nullopt;
        h = end_hint;
    }
    hint = h;
    return next;
}

}  // namespace tr
