#include <mesh/copyleft/detail/tetgen_plc.h>
#include <mesh/copyleft/tetgen_mesher.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace tr {
namespace {

// TetGen 1.5's switch letters that make sense here (see tetgen_mesher.h for those left out).
constexpr std::string_view kAllowedSwitchLetters = "pYqaAOSTXMcdzfenvJBCQVRLxDo";

Result<std::string> make_switches(const TetgenOptions& options) {
    std::string switches = "pQ";
    if (!std::isfinite(options.quality_ratio) || options.quality_ratio < 0 ||
        (options.quality_ratio > 0 && options.quality_ratio < 1.0)) {
        return make_error(ErrorCode::kInvalidArgument,
                          "quality_ratio must be 0 (none) or at least 1 (TetGen may not "
                          "terminate below), got " +
                              std::to_string(options.quality_ratio));
    }
    if (!std::isfinite(options.max_volume) || options.max_volume < 0) {
        return make_error(
            ErrorCode::kInvalidArgument,
            "max_volume must be 0 (none) or positive, got " + std::to_string(options.max_volume));
    }
    // (Appended piecewise: GCC 12 warns falsely on "q" + std::string, -Wrestrict.)
    if (options.quality_ratio > 0) {
        switches += 'q';
        switches += detail::tetgen_number(options.quality_ratio);
    }
    if (options.max_volume > 0) {
        switches += 'a';
        switches += detail::tetgen_number(options.max_volume);
        // TetGen's final optimization (flips, smoothing) can enlarge tets up to ~30% past the
        // bound; without it the bound holds for every tet. An 'O' in extra_switches wins.
        switches += "O0";
    }
    for (char c : options.extra_switches) {
        const bool ok = (c >= '0' && c <= '9') || c == '.' || c == '/' || c == ',' ||
                        kAllowedSwitchLetters.find(c) != std::string_view::npos;
        if (!ok) {
            std::string message = "TetGen switch '";
            message.push_back(c);
            message += "' in '" + options.extra_switches + "' is not accepted (allowed: letters ";
            message += kAllowedSwitchLetters;
            message += ", digits, . / ,)";
            return make_error(ErrorCode::kInvalidArgument, std::move(message));
        }
    }
    return switches + options.extra_switches;
}

Status check_surface(const SurfaceMesh& surface) {
    const std::string where = surface.name.empty() ? std::string() : surface.name;
    if (surface.triangles.empty()) {
        return make_error(ErrorCode::kInvalidMesh, "the surface has no triangles", where);
    }
    for (std::size_t i = 0; i < surface.points.size(); ++i) {
        const Vec3& p = surface.points[i];
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
            return make_error(ErrorCode::kInvalidMesh,
                              "surface point " + std::to_string(i) + " has a non-finite coordinate",
                              where);
        }
    }
    for (const Vec3& h : surface.holes) {
        if (!std::isfinite(h.x) || !std::isfinite(h.y) || !std::isfinite(h.z)) {
            return make_error(ErrorCode::kInvalidMesh, "a hole point has a non-finite coordinate",
                              where);
        }
    }
    std::vector<std::uint64_t> edges;
    edges.reserve(surface.triangles.size() * 3);
    for (std::size_t t = 0; t < surface.triangles.size(); ++t) {
        const auto& tri = surface.triangles[t];
        for (std::uint32_t v : tri) {
            if (v >= surface.points.size()) {
                return make_error(ErrorCode::kInvalidMesh,
                                  "triangle " + std::to_string(t) + " uses point " +
                                      std::to_string(v) + " but there are only " +
                                      std::to_string(surface.points.size()),
                                  where);
            }
        }
        if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2]) {
            return make_error(ErrorCode::kInvalidMesh,
                              "triangle " + std::to_string(t) + " repeats a point", where);
        }
        for (int e = 0; e < 3; ++e) {
            const std::uint64_t a = tri[e];
            const std::uint64_t b = tri[(e + 1) % 3];
            edges.push_back((std::min(a, b) << 32) | std::max(a, b));
        }
    }
    std::sort(edges.begin(), edges.end());
    for (std::size_t i = 0; i < edges.size();) {
        std::size_t j = i + 1;
        while (j < edges.size() && edges[j] == edges[i]) ++j;
        if (j - i == 1) {
            return make_error(ErrorCode::kInvalidMesh,
                              "the surface is not closed: edge (" + std::to_string(edges[i] >> 32) +
                                  ", " + std::to_string(edges[i] & 0xffffffffu) +
                                  ") belongs to one triangle only",
                              where);
        }
        i = j;
    }
    // A closed surface with nothing inside (every point in one plane, or parts whose volumes
    // cancel): TetGen aborts on it (signal 6) instead of saying so. The volume by the divergence
    // theorem, about the bounds' centre, against the bounds' cube: exactly flat gives rounding
    // only (~1e-16); the threshold is far below any real solid's.
    Vec3 lo = surface.points[surface.triangles[0][0]], hi = lo;
    for (const auto& tri : surface.triangles) {
        for (std::uint32_t v : tri) {
            lo = glm::min(lo, surface.points[v]);
            hi = glm::max(hi, surface.points[v]);
        }
    }
    const Vec3 centre = 0.5 * (lo + hi);
    double six_volume = 0;
    for (const auto& tri : surface.triangles) {
        const Vec3 a = surface.points[tri[0]] - centre;
        six_volume += glm::dot(a, glm::cross(surface.points[tri[1]] - centre - a,
                                             surface.points[tri[2]] - centre - a));
    }
    const double size = glm::length(hi - lo);
    if (!(std::abs(six_volume) / 6.0 > 1e-12 * size * size * size)) {
        return make_error(ErrorCode::kInvalidMesh,
                          "the surface encloses no volume (it is flat, or its parts cancel): "
                          "there is nothing inside for TetGen to mesh",
                          where);
    }
    return {};
}

}  // namespace

Result<TetMesh> tetgen_mesh_surface(const SurfaceMesh& surface, const TetgenOptions& options) {
    TR_TRY(const std::string switches, make_switches(options));
    TR_TRY_STATUS(check_surface(surface));
    if (options.max_volume > 0) {
        // The enclosed volume by the divergence theorem (cavities, wound the other way,
        // subtract; either way the size of the sum bounds what TetGen must fill).
        double six_volume = 0;
        for (const auto& t : surface.triangles) {
            const Vec3& a = surface.points[t[0]];
            six_volume +=
                glm::dot(a, glm::cross(surface.points[t[1]] - a, surface.points[t[2]] - a));
        }
        const double at_least = std::abs(six_volume) / 6.0 / options.max_volume;
        if (at_least > options.max_tets) {
            char text[200];
            std::snprintf(text, sizeof text,
                          "--max-volume %g asks for at least %.3g tets (the surface encloses "
                          "%g), more than the %.3g allowed",
                          options.max_volume, at_least, std::abs(six_volume) / 6.0,
                          options.max_tets);
            return make_error(ErrorCode::kInvalidArgument, text, surface.name);
        }
    }

    detail::TetgenPlc plc;
    plc.points = surface.points;
    plc.triangles = surface.triangles;
    plc.holes = surface.holes;
    TR_TRY(detail::TetgenResult meshed, detail::run_tetgen(plc, switches));
    if (meshed.tets.empty()) {
        return make_error(ErrorCode::kInvalidMesh,
                          "TetGen made no tetrahedra (is the surface closed and are the hole "
                          "points inside cavities?)",
                          surface.name);
    }

    // Keep the points tets use (input points whose region was carved away drop out).
    std::vector<PointId> new_index(meshed.points.size(), kNoCell);
    for (const Tet& tet : meshed.tets) {
        for (PointId p : tet) new_index[p] = 0;
    }
    std::vector<Vec3> points;
    for (std::size_t i = 0; i < meshed.points.size(); ++i) {
        if (new_index[i] == kNoCell) continue;
        new_index[i] = static_cast<PointId>(points.size());
        points.push_back(meshed.points[i]);
    }
    for (Tet& tet : meshed.tets) {
        for (PointId& p : tet) p = new_index[p];
    }
    return TetMesh::create(std::move(points), std::move(meshed.tets));
}

}  // namespace tr
