#include <flowvol/point_locator.h>

#include <algorithm>
#include <cmath>

namespace tr {
namespace {

constexpr int kMaxWalk = 4096;  // steps before the walk gives up on a hint

}  // namespace

PointLocator::PointLocator(const TetMesh& mesh, const FaceAdjacency& adjacency)
    : mesh_(mesh), adjacency_(adjacency), bounds_(mesh.bounds()) {
    pad_ = 1e-9 * bounds_.diagonal();
    const std::size_t n = std::max<std::size_t>(mesh.num_real_tets(), 1);
    const Vec3 size = glm::max(bounds_.size(), Vec3(1e-300));
    // About one grid cell per tet, shaped like the bounds.
    const double cell = std::cbrt(size.x * size.y * size.z / static_cast<double>(n));
    nx_ = std::clamp(static_cast<int>(size.x / cell), 1, 1024);
    ny_ = std::clamp(static_cast<int>(size.y / cell), 1, 1024);
    nz_ = std::clamp(static_cast<int>(size.z / cell), 1, 1024);
    cell_size_ = size / Vec3(nx_, ny_, nz_);
    const std::size_t num_cells = static_cast<std::size_t>(nx_) * ny_ * nz_;
    cell_start_.assign(num_cells + 1, 0);
    auto for_each_cell = [&](CellId t, auto&& fn) {
        Bounds3 b;
        for (PointId p : mesh.tet(t)) b.extend(mesh.point(p));
        const Vec3 lo = (b.lo - bounds_.lo) / cell_size_, hi = (b.hi - bounds_.lo) / cell_size_;
        const int x0 = std::clamp(static_cast<int>(lo.x), 0, nx_ - 1);
        const int y0 = std::clamp(static_cast<int>(lo.y), 0, ny_ - 1);
        const int z0 = std::clamp(static_cast<int>(lo.z), 0, nz_ - 1);
        const int x1 = std::clamp(static_cast<int>(hi.x), 0, nx_ - 1);
        const int y1 = std::clamp(static_cast<int>(hi.y), 0, ny_ - 1);
        const int z1 = std::clamp(static_cast<int>(hi.z), 0, nz_ - 1);
        for (int z = z0; z <= z1; ++z)
            for (int y = y0; y <= y1; ++y)
                for (int x = x0; x <= x1; ++x)
                    fn((static_cast<std::size_t>(z) * ny_ + y) * nx_ + x);
    };
    for (CellId t = 0; t < mesh.num_real_tets(); ++t) {
        for_each_cell(t, [&](std::size_t c) { ++cell_start_[c + 1]; });
    }
    for (std::size_t c = 0; c < num_cells; ++c) cell_start_[c + 1] += cell_start_[c];
    cell_tets_.resize(cell_start_.back());
    std::vector<std::uint32_t> fill(cell_start_.begin(), cell_start_.end() - 1);
    for (CellId t = 0; t < mesh.num_real_tets(); ++t) {
        for_each_cell(t, [&](std::size_t c) { cell_tets_[fill[c]++] = t; });
    }
}

std::size_t PointLocator::grid_index(const Vec3& p) const {
    const Vec3 q = (p - bounds_.lo) / cell_size_;
    const int x = std::clamp(static_cast<int>(q.x), 0, nx_ - 1);
    const int y = std::clamp(static_cast<int>(q.y), 0, ny_ - 1);
    const int z = std::clamp(static_cast<int>(q.z), 0, nz_ - 1);
    return (static_cast<std::size_t>(z) * ny_ + y) * nx_ + x;
}

bool PointLocator::walk(const Vec3& p, CellId t, Location& out) const {
    for (int step = 0; step < kMaxWalk && t != kNoCell && !mesh_.is_virtual(t); ++step) {
        const auto w = barycentric(t, p);
        int worst = 0;
        for (int k = 1; k < 4; ++k) {
            if (w[k] < w[worst]) worst = k;
        }
        if (w[worst] >= kInsideTolerance) {
            out = {t, w};
            return true;
        }
        // Face `worst` is opposite vertex `worst`: the point lies beyond it.
        t = adjacency_.neighbors[t][worst];
    }
    return false;
}

std::optional<Location> PointLocator::locate_slow(const Vec3& p, CellId hint) const {
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) return std::nullopt;
    const double pad = pad_;
    if (p.x < bounds_.lo.x - pad || p.y < bounds_.lo.y - pad || p.z < bounds_.lo.z - pad ||
        p.x > bounds_.hi.x + pad || p.y > bounds_.hi.y + pad || p.z > bounds_.hi.z + pad) {
        return std::nullopt;
    }
    Location out;
    if (hint != kNoCell && hint < mesh_.num_real_tets() && walk(p, hint, out)) return out;
    // The grid cell's tets: test each (a walk from one can leave a non-convex mesh).
    const std::size_t c = grid_index(p);
    for (std::uint32_t i = cell_start_[c]; i < cell_start_[c + 1]; ++i) {
        const auto w = barycentric(cell_tets_[i], p);
        if (*std::min_element(w.begin(), w.end()) >= kInsideTolerance) {
            return Location{cell_tets_[i], w};
        }
    }
    return std::nullopt;
}

}  // namespace tr
