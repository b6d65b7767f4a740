#include <core/parallel.h>
#include <project/splat/point_spacing.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <queue>

namespace tr {
namespace {

// A k-d tree over the points (median splits across the widest axis, leaves of up to 8): the k
// nearest in O(k log n) whatever the points' clustering (a curvilinear grid's boundary layer
// packs thousands of points where a uniform grid would expect four).
class KdTree {
  public:
    explicit KdTree(std::span<const Vec3> points) : points_(points), index_(points.size()) {
        for (std::size_t i = 0; i < index_.size(); ++i) index_[i] = static_cast<std::uint32_t>(i);
        nodes_.reserve(2 * points.size() / kLeaf + 2);
        build(0, static_cast<std::uint32_t>(index_.size()));
    }

    // The squared distance from point `self` to its k-th nearest other point (k <= the other
    // points' count).
    double kth_nearest_squared(std::uint32_t self, int k) const {
        std::priority_queue<double> nearest;  // the k smallest so far, largest on top
        search(0, self, k, nearest);
        return nearest.top();
    }

  private:
    static constexpr std::uint32_t kLeaf = 8;
    struct Node {
        std::uint32_t begin, end;  // index_ range
        int axis = -1;             // -1: a leaf
        double split = 0;
        std::uint32_t left = 0, right = 0;
    };

    std::uint32_t build(std::uint32_t begin, std::uint32_t end) {
        const std::uint32_t id = static_cast<std::uint32_t>(nodes_.size());
        nodes_.push_back({begin, end});
        if (end - begin <= kLeaf) return id;
        Vec3 lo = points_[index_[begin]], hi = lo;
        for (std::uint32_t i = begin; i < end; ++i) {
            lo = glm::min(lo, points_[index_[i]]), hi = glm::max(hi, points_[index_[i]]);
        }
        const Vec3 extent = hi - lo;
        const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0
                         : extent.y >= extent.z                       ? 1
                                                                      : 2;
        if (!(extent[axis] > 0)) return id;  // all coincide: a leaf of any size
        const std::uint32_t mid = begin + (end - begin) / 2;
        std::nth_element(
            index_.begin() + begin, index_.begin() + mid, index_.begin() + end,
            [&](std::uint32_t a, std::uint32_t b) { return points_[a][axis] < points_[b][axis]; });
        const double split = points_[index_[mid]][axis];
        const std::uint32_t left = build(begin, mid);
        const std::uint32_t right = build(mid, end);
        Node& node = nodes_[id];
        node.axis = axis, node.split = split, node.left = left, node.right = right;
        return id;
    }

    void search(std::uint32_t id, std::uint32_t self, int k,
                std::priority_queue<double>& nearest) const {
        const Node& node = nodes_[id];
        const Vec3& p = points_[self];
        if (node.axis < 0) {
            for (std::uint32_t i = node.begin; i < node.end; ++i) {
                if (index_[i] == self) continue;
                const Vec3 d = points_[index_[i]] - p;
                const double d2 = glm::dot(d, d);
                if (static_cast<int>(nearest.size()) < k) {
                    nearest.push(d2);
                } else if (d2 < nearest.top()) {
                    nearest.pop();
                    nearest.push(d2);
                }
            }
            return;
        }
        // Points left of the median are <= split, right of it >= split.
        const double gap = p[node.axis] - node.split;
        const std::uint32_t near = gap < 0 ? node.left : node.right;
        const std::uint32_t far = gap < 0 ? node.right : node.left;
        search(near, self, k, nearest);
        if (static_cast<int>(nearest.size()) < k || gap * gap < nearest.top()) {
            search(far, self, k, nearest);
        }
    }

    std::span<const Vec3> points_;
    std::vector<std::uint32_t> index_;
    std::vector<Node> nodes_;
};

}  // namespace

std::vector<float> local_spacing(std::span<const Vec3> points) {
    const std::size_t n = points.size();
    std::vector<float> h(n, 0.0f);
    if (n < 2) return h;
    if (n <= static_cast<std::size_t>(kSpacingNeighbour)) {
        double widest = 0;
        for (std::size_t i = 0; i < n; ++i) {
            for (std::size_t j = i + 1; j < n; ++j) {
                widest = std::max(widest, glm::length(points[i] - points[j]));
            }
        }
        std::fill(h.begin(), h.end(), static_cast<float>(0.5 * widest));
        return h;
    }
    const KdTree tree(points);
    parallel_for(0, n, 256, [&](std::size_t i) {
        const double d2 =
            tree.kth_nearest_squared(static_cast<std::uint32_t>(i), kSpacingNeighbour);
        h[i] = static_cast<float>(0.5 * std::sqrt(d2));
    });
    return h;
}

}  // namespace tr
