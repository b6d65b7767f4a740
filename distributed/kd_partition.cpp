#include <distributed/kd_partition.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <tuple>

namespace tr {
namespace {

int longest_axis(const Bounds3& box) {
    const Vec3 size = box.size();
    int axis = 0;
    if (size.y > size[axis]) axis = 1;
    if (size.z > size[axis]) axis = 2;
    return axis;
}

// The middle of the gap between two distinct (sorted) coordinates nearest index `target`, or the
// coordinate there when all are equal.
double gap_near(const std::vector<double>& sorted, std::ptrdiff_t target) {
    const auto n = static_cast<std::ptrdiff_t>(sorted.size());
    const auto in_gap = [&](std::ptrdiff_t j) {
        return j >= 1 && j < n && sorted[j - 1] < sorted[j];
    };
    for (std::ptrdiff_t d = 0; d < n; ++d) {
        for (const std::ptrdiff_t j : {target - d, target + d}) {
            if (in_gap(j)) return 0.5 * (sorted[j - 1] + sorted[j]);
        }
    }
    return sorted[static_cast<std::size_t>(std::clamp<std::ptrdiff_t>(target, 0, n - 1))];
}

// The plane along `axis` that leaves about `fraction` of the samples (by centroid) below it:
// among the candidates within 2.5% of that count (the samples' own bounds, and the gap between
// centroids nearest the count), the one that cuts the fewest samples, then the one nearest
// the count. Inside [lo, hi].
double choose_split(const std::vector<CellSample>& samples, int axis, double fraction, double lo,
                    double hi) {
    const std::size_t n = samples.size();
    if (n == 0) return 0.5 * (lo + hi);
    std::vector<double> centre(n), low(n), high(n);
    for (std::size_t i = 0; i < n; ++i) {
        centre[i] = samples[i].centroid[axis];
        low[i] = samples[i].bounds.lo[axis];
        high[i] = samples[i].bounds.hi[axis];
    }
    std::sort(centre.begin(), centre.end());
    std::sort(low.begin(), low.end());
    std::sort(high.begin(), high.end());
    const auto count_below = [](const std::vector<double>& v, double s) {
        return static_cast<std::ptrdiff_t>(std::lower_bound(v.begin(), v.end(), s) - v.begin());
    };
    const auto at_most = [](const std::vector<double>& v, double s) {
        return static_cast<std::ptrdiff_t>(std::upper_bound(v.begin(), v.end(), s) - v.begin());
    };
    const auto target =
        static_cast<std::ptrdiff_t>(std::llround(fraction * static_cast<double>(n)));
    const std::ptrdiff_t slack = std::max<std::ptrdiff_t>(1, static_cast<std::ptrdiff_t>(n / 40));
    struct Score {
        std::ptrdiff_t cuts, off;
        double at;
    };
    Score best{std::numeric_limits<std::ptrdiff_t>::max(), 0, 0.5 * (lo + hi)};
    const auto consider = [&](double s) {
        s = std::clamp(s, lo, hi);
        const std::ptrdiff_t off = std::abs(count_below(centre, s) - target);
        if (off > slack && best.cuts != std::numeric_limits<std::ptrdiff_t>::max()) return;
        // Cells reaching across the plane: those starting below it less those ending at it.
        const std::ptrdiff_t cuts = count_below(low, s) - at_most(high, s);
        const Score score{off > slack ? std::numeric_limits<std::ptrdiff_t>::max() - 1 : cuts, off,
                          s};
        if (std::tie(score.cuts, score.off, score.at) < std::tie(best.cuts, best.off, best.at)) {
            best = score;
        }
    };
    consider(gap_near(centre, target));
    // The values whose count below stays within the slack: (centre[i0 - 1], centre[i1]].
    const std::ptrdiff_t i0 = std::max<std::ptrdiff_t>(target - slack, 0);
    const std::ptrdiff_t i1 =
        std::min<std::ptrdiff_t>(target + slack, static_cast<std::ptrdiff_t>(n));
    const double v0 = i0 == 0 ? lo : centre[i0 - 1];
    const double v1 = i1 >= static_cast<std::ptrdiff_t>(n) ? hi : centre[i1];
    for (const std::vector<double>* ends : {&low, &high}) {
        auto it = std::upper_bound(ends->begin(), ends->end(), v0);
        for (; it != ends->end() && *it <= v1; ++it) {
            if (it != ends->begin() && *(it - 1) == *it) continue;
            consider(*it);
        }
    }
    return best.at;
}

}  // namespace

KdPartition::KdPartition(const Bounds3& domain, int parts) : num_parts_(parts) {
    KdNode root;
    root.part = 0;
    root.box = domain;
    nodes_.push_back(root);
    leaf_of_part_.assign(static_cast<std::size_t>(parts), 0);
}

KdPartition KdPartition::balanced(std::span<const CellSample> samples, int parts,
                                  const Bounds3& domain) {
    KdPartition partition(domain, std::max(parts, 1));
    partition.nodes_.clear();
    struct Pending {
        int node;
        int parts;
        int first_part;
        std::vector<CellSample> samples;
    };
    partition.nodes_.push_back(KdNode{.box = domain});
    std::vector<Pending> stack;
    stack.push_back({0, partition.num_parts_, 0, {samples.begin(), samples.end()}});
    while (!stack.empty()) {
        Pending job = std::move(stack.back());
        stack.pop_back();
        if (job.parts == 1) {
            partition.nodes_[job.node].part = job.first_part;
            partition.leaf_of_part_[job.first_part] = job.node;
            continue;
        }
        const Bounds3 box = partition.nodes_[job.node].box;
        const int axis = longest_axis(box);
        const int parts_below = job.parts / 2;
        const double split =
            choose_split(job.samples, axis, static_cast<double>(parts_below) / job.parts,
                         box.empty() ? 0.0 : box.lo[axis], box.empty() ? 0.0 : box.hi[axis]);
        Pending below{static_cast<int>(partition.nodes_.size()), parts_below, job.first_part, {}};
        Pending above{below.node + 1, job.parts - parts_below, job.first_part + parts_below, {}};
        for (const CellSample& s : job.samples) {
            (s.centroid[axis] < split ? below : above).samples.push_back(s);
        }
        KdNode below_node, above_node;
        below_node.box = above_node.box = box;
        if (!box.empty()) {
            below_node.box.hi[axis] = split;
            above_node.box.lo[axis] = split;
        }
        KdNode& node = partition.nodes_[job.node];
        node.axis = axis;
        node.split = split;
        node.below = below.node;
        node.above = above.node;
        partition.nodes_.push_back(below_node);
        partition.nodes_.push_back(above_node);
        stack.push_back(std::move(above));
        stack.push_back(std::move(below));
    }
    return partition;
}

std::vector<int> KdPartition::front_to_back(const CameraFrame& camera) const {
    std::vector<int> order;
    order.reserve(static_cast<std::size_t>(num_parts_));
    std::vector<int> stack{0};
    while (!stack.empty()) {
        const KdNode& node = nodes_[stack.back()];
        stack.pop_back();
        if (node.axis < 0) {
            order.push_back(node.part);
            continue;
        }
        // The side the eye is on (or, orthographic, the side the view comes from) is in front.
        const bool below_first = camera.orthographic() ? camera.forward()[node.axis] >= 0
                                                       : camera.eye()[node.axis] <= node.split;
        stack.push_back(below_first ? node.above : node.below);
        stack.push_back(below_first ? node.below : node.above);
    }
    return order;
}

}  // namespace tr
