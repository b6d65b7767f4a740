#include <mesh/tet_mesh.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace tr {
namespace {

double longest_edge_squared(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
    auto l2 = [](const Vec3& p, const Vec3& q) { return glm::dot(p - q, p - q); };
    return std::max({l2(a, b), l2(a, c), l2(a, d), l2(b, c), l2(b, d), l2(c, d)});
}

// Flips negative tets and reports whether `tet` is degenerate.
bool orient_or_reject(const std::vector<Vec3>& points, Tet& tet, double tolerance,
                      TetRepairReport& report) {
    if (tet[0] == tet[1] || tet[0] == tet[2] || tet[0] == tet[3] || tet[1] == tet[2] ||
        tet[1] == tet[3] || tet[2] == tet[3]) {
        return false;
    }
    const Vec3& a = points[tet[0]];
    const Vec3& b = points[tet[1]];
    const Vec3& c = points[tet[2]];
    const Vec3& d = points[tet[3]];
    const double six_volume = orient3d(a, b, c, d);
    const double l2 = longest_edge_squared(a, b, c, d);
    if (!(std::abs(six_volume) > tolerance * l2 * std::sqrt(l2))) return false;
    if (six_volume < 0) {
        std::swap(tet[2], tet[3]);
        // orient3d of the flipped tet is another rounding of the same determinant: for a tet
        // flat to within rounding (kept when the tolerance is 0, as Delaunay meshes are) it can
        // come out <= 0 too. Such a tet has no orientation to give: it is degenerate.
        if (!(orient3d(points[tet[0]], points[tet[1]], points[tet[2]], points[tet[3]]) > 0))
            return false;
        ++report.num_reoriented;
    }
    return true;
}

bool is_finite(const Vec3& p) {
    return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
}

}  // namespace

Result<TetMesh> TetMesh::create(std::vector<Vec3> points, std::vector<Tet> tets,
                                std::vector<CellId> source_cells,
                                const TetMeshCreateOptions& options, TetRepairReport* report) {
    if (!source_cells.empty() && source_cells.size() != tets.size()) {
        return make_error(ErrorCode::kInvalidArgument,
                          "source_cells has " + std::to_string(source_cells.size()) +
                              " entries for " + std::to_string(tets.size()) + " tets");
    }
    if (points.size() >= kNoCell || tets.size() >= kNoCell) {
        return make_error(ErrorCode::kInvalidArgument,
                          "mesh too large: at most 2^32 - 1 points and tets");
    }
    if (source_cells.empty()) {
        source_cells.resize(tets.size());
        for (std::size_t t = 0; t < tets.size(); ++t) source_cells[t] = static_cast<CellId>(t);
    }
    const std::size_t num_points = points.size();
    for (std::size_t t = 0; t < tets.size(); ++t) {
        for (PointId p : tets[t]) {
            if (p >= num_points) {
                return make_error(ErrorCode::kInvalidMesh,
                                  "tet " + std::to_string(t) + " uses point " + std::to_string(p) +
                                      " but there are only " + std::to_string(num_points),
                                  "tet " + std::to_string(t));
            }
            if (!is_finite(points[p])) {
                return make_error(ErrorCode::kInvalidMesh,
                                  "point " + std::to_string(p) + " has a non-finite coordinate",
                                  "point " + std::to_string(p));
            }
        }
    }
    TetRepairReport local;
    std::size_t kept = 0;
    for (std::size_t t = 0; t < tets.size(); ++t) {
        Tet tet = tets[t];
        if (orient_or_reject(points, tet, options.degenerate_tolerance, local)) {
            tets[kept] = tet;
            source_cells[kept] = source_cells[t];
            ++kept;
        } else {
            ++local.num_degenerate;
        }
    }
    tets.resize(kept);
    source_cells.resize(kept);
    if (report) *report = local;

    TetMesh mesh;
    mesh.points_ = std::move(points);
    mesh.tets_ = std::move(tets);
    mesh.source_cells_ = std::move(source_cells);
    mesh.num_real_tets_ = mesh.tets_.size();
    mesh.num_real_points_ = mesh.points_.size();
    return mesh;
}

double TetMesh::tet_volume(CellId t) const {
    const Tet& v = tets_[t];
    return tr::tet_volume(points_[v[0]], points_[v[1]], points_[v[2]], points_[v[3]]);
}

double TetMesh::real_volume() const {
    double sum = 0.0;
    for (std::size_t t = 0; t < num_real_tets_; ++t) sum += tet_volume(static_cast<CellId>(t));
    return sum;
}

Bounds3 TetMesh::bounds() const {
    Bounds3 b;
    if (num_real_tets_ == 0) {
        for (const Vec3& p : points_) b.extend(p);
        return b;
    }
    std::vector<bool> used(points_.size(), false);
    for (std::size_t t = 0; t < num_real_tets_; ++t) {
        for (PointId p : tets_[t]) used[p] = true;
    }
    for (std::size_t p = 0; p < points_.size(); ++p) {
        if (used[p]) b.extend(points_[p]);
    }
    return b;
}

Status TetMesh::add_point_field(Field field) {
    if (field.num_components < 1 || field.num_tuples() != points_.size() ||
        field.num_tuples() * static_cast<std::size_t>(field.num_components) !=
            std::visit([](const auto& v) { return v.size(); }, field.values)) {
        return make_error(ErrorCode::kInvalidArgument,
                          "point field '" + field.name + "' has " +
                              std::to_string(field.num_tuples()) + " tuples for " +
                              std::to_string(points_.size()) + " points");
    }
    if (find_field(point_fields_, field.name)) {
        return make_error(ErrorCode::kInvalidArgument,
                          "point field '" + field.name + "' already exists");
    }
    point_fields_.push_back(std::move(field));
    return {};
}

Status TetMesh::add_cell_field(Field field) {
    const std::size_t n = field.num_tuples();
    if (field.num_components < 1 || (n != tets_.size() && n != num_real_tets_)) {
        return make_error(ErrorCode::kInvalidArgument, "cell field '" + field.name + "' has " +
                                                           std::to_string(n) + " tuples for " +
                                                           std::to_string(tets_.size()) + " tets");
    }
    if (find_field(cell_fields_, field.name)) {
        return make_error(ErrorCode::kInvalidArgument,
                          "cell field '" + field.name + "' already exists");
    }
    const std::size_t full = tets_.size() * static_cast<std::size_t>(field.num_components);
    std::visit([full](auto& v) { v.resize(full); }, field.values);
    cell_fields_.push_back(std::move(field));
    return {};
}

Status TetMesh::append_virtual(std::vector<Vec3> new_points, std::vector<Tet> virtual_tets) {
    const std::size_t first_new = points_.size();
    points_.insert(points_.end(), new_points.begin(), new_points.end());
    if (points_.size() >= kNoCell || tets_.size() + virtual_tets.size() >= kNoCell) {
        points_.resize(first_new);
        return make_error(ErrorCode::kInvalidArgument, "mesh too large after convexification");
    }
    TetRepairReport unused;
    std::vector<Tet> accepted;
    accepted.reserve(virtual_tets.size());
    for (Tet tet : virtual_tets) {
        for (PointId p : tet) {
            if (p >= points_.size()) {
                points_.resize(first_new);
                return make_error(ErrorCode::kInvalidArgument,
                                  "virtual tet uses point " + std::to_string(p) + " out of range");
            }
        }
        if (orient_or_reject(points_, tet, 0.0, unused)) accepted.push_back(tet);
    }
    tets_.insert(tets_.end(), accepted.begin(), accepted.end());
    source_cells_.resize(tets_.size(), kNoCell);
    for (Field& f : point_fields_) {
        const std::size_t n = points_.size() * static_cast<std::size_t>(f.num_components);
        std::visit([n](auto& v) { v.resize(n); }, f.values);
    }
    for (Field& f : cell_fields_) {
        const std::size_t n = tets_.size() * static_cast<std::size_t>(f.num_components);
        std::visit([n](auto& v) { v.resize(n); }, f.values);
    }
    return {};
}

void TetMesh::remove_virtual() {
    tets_.resize(num_real_tets_);
    source_cells_.resize(num_real_tets_);
    points_.resize(num_real_points_);
    for (Field& f : point_fields_) {
        const std::size_t n = points_.size() * static_cast<std::size_t>(f.num_components);
        std::visit([n](auto& v) { v.resize(n); }, f.values);
    }
    for (Field& f : cell_fields_) {
        const std::size_t n = tets_.size() * static_cast<std::size_t>(f.num_components);
        std::visit([n](auto& v) { v.resize(n); }, f.values);
    }
}

std::size_t TetMesh::byte_size() const {
    std::size_t bytes = points_.size() * sizeof(Vec3) + tets_.size() * sizeof(Tet) +
                        source_cells_.size() * sizeof(CellId);
    for (const Field& f : point_fields_) bytes += f.byte_size();
    for (const Field& f : cell_fields_) bytes += f.byte_size();
    return bytes;
}

}  // namespace tr
