// The k-d partition: balanced by count, its boxes tile the domain, grid planes fall between
// cell layers, and its front-to-back order holds on every ray (checked by brute force: each
// ray's entry into every box it meets).
#include <distributed/kd_partition.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

namespace tr {
namespace {

// The part a point falls in (below a plane when strictly less than it).
int part_of(const KdPartition& partition, const Vec3& p) {
    int node = 0;
    while (partition.nodes()[node].axis >= 0) {
        const KdNode& n = partition.nodes()[node];
        node = p[n.axis] < n.split ? n.below : n.above;
    }
    return partition.nodes()[node].part;
}

// Points as samples of cells of no size.
std::vector<CellSample> samples_of(const std::vector<Vec3>& points) {
    std::vector<CellSample> samples;
    for (const Vec3& p : points) {
        CellSample s;
        s.centroid = p;
        s.bounds.extend(p);
        samples.push_back(s);
    }
    return samples;
}

double box_volume(const Bounds3& b) {
    const Vec3 s = b.size();
    return s.x * s.y * s.z;
}

std::vector<Vec3> random_points(std::size_t n, const Bounds3& box, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<Vec3> points(n);
    for (Vec3& p : points) {
        // Denser towards lo: a skewed distribution, so that equal counts mean unequal boxes.
        const Vec3 t(u(rng) * u(rng), u(rng), std::sqrt(u(rng)));
        p = box.lo + t * box.size();
    }
    return points;
}

Bounds3 domain_box() {
    Bounds3 box;
    box.extend(Vec3(-1.0, 0.0, 2.0));
    box.extend(Vec3(3.0, 1.5, 2.5));
    return box;
}

TEST(KdPartition, BalancesCountsAcrossParts) {
    const Bounds3 domain = domain_box();
    const std::vector<Vec3> points = random_points(60000, domain, 7);
    for (int parts = 1; parts <= 9; ++parts) {
        SCOPED_TRACE(parts);
        const KdPartition partition = KdPartition::balanced(samples_of(points), parts, domain);
        ASSERT_EQ(partition.num_parts(), parts);
        std::vector<double> count(parts, 0.0);
        for (const Vec3& p : points) count[part_of(partition, p)] += 1;
        const double mean = static_cast<double>(points.size()) / parts;
        double worst = 0;
        for (double c : count) worst = std::max(worst, std::abs(c - mean) / mean);
        // Measured: at most 0.0003 (points: no plane cuts any, so each is at its quantile).
        EXPECT_LE(worst, 0.002);
    }
}

TEST(KdPartition, BoxesTileTheDomain) {
    const Bounds3 domain = domain_box();
    const std::vector<Vec3> points = random_points(5000, domain, 3);
    for (int parts : {1, 2, 3, 5, 8, 13}) {
        SCOPED_TRACE(parts);
        const KdPartition partition = KdPartition::balanced(samples_of(points), parts, domain);
        double volume = 0;
        for (int p = 0; p < parts; ++p) {
            const Bounds3& b = partition.box(p);
            EXPECT_TRUE(glm::all(glm::greaterThanEqual(b.lo, domain.lo)));
            EXPECT_TRUE(glm::all(glm::lessThanEqual(b.hi, domain.hi)));
            volume += box_volume(b);
        }
        EXPECT_NEAR(volume, box_volume(domain), 1e-12 * box_volume(domain));
        // Every point lies in the box of the part it falls in.
        for (const Vec3& q : random_points(2000, domain, 11)) {
            const Bounds3& b = partition.box(part_of(partition, q));
            EXPECT_TRUE(glm::all(glm::greaterThanEqual(q, b.lo)) &&
                        glm::all(glm::lessThanEqual(q, b.hi)));
        }
    }
}

TEST(KdPartition, PlanesFallBetweenTheLayersOfAGridsCells) {
    // A 40 x 24 x 16 grid of unit cells, each as six tets (their centroids at a quarter, half
    // and three quarters of the cell along each axis): the planes between layers cut none.
    std::vector<CellSample> cells;
    for (int k = 0; k < 16; ++k) {
        for (int j = 0; j < 24; ++j) {
            for (int i = 0; i < 40; ++i) {
                for (const Vec3 at :
                     {Vec3(0.25, 0.5, 0.75), Vec3(0.75, 0.25, 0.5), Vec3(0.5, 0.75, 0.25),
                      Vec3(0.25, 0.75, 0.5), Vec3(0.75, 0.5, 0.25), Vec3(0.5, 0.25, 0.75)}) {
                    CellSample s;
                    s.centroid = Vec3(i, j, k) + at;
                    s.bounds.extend(Vec3(i, j, k));
                    s.bounds.extend(Vec3(i + 1, j + 1, k + 1));
                    cells.push_back(s);
                }
            }
        }
    }
    Bounds3 domain;
    domain.extend(Vec3(0.0));
    domain.extend(Vec3(40, 24, 16));
    // Part counts whose balance every node can meet within 2.5% on a layer boundary (7 cannot:
    // one node halves 17 layers).
    for (int parts : {2, 3, 4, 5, 6, 8, 12, 16}) {
        SCOPED_TRACE(parts);
        const KdPartition partition = KdPartition::balanced(cells, parts, domain);
        for (const KdNode& node : partition.nodes()) {
            if (node.axis < 0) continue;
            EXPECT_EQ(node.split, std::round(node.split)) << "axis " << node.axis;
        }
    }
}

TEST(KdPartition, MorePartsThanSamplesStillTileTheDomain) {
    const Bounds3 domain = domain_box();
    const std::vector<Vec3> two = random_points(2, domain, 5);
    for (int parts : {3, 4, 7}) {
        const KdPartition partition = KdPartition::balanced(samples_of(two), parts, domain);
        double volume = 0;
        for (int p = 0; p < parts; ++p) volume += box_volume(partition.box(p));
        EXPECT_NEAR(volume, box_volume(domain), 1e-12 * box_volume(domain));
    }
    const KdPartition none = KdPartition::balanced({}, 4, domain);
    double volume = 0;
    for (int p = 0; p < 4; ++p) volume += box_volume(none.box(p));
    EXPECT_NEAR(volume, box_volume(domain), 1e-12 * box_volume(domain));
}

// Where the ray enters and leaves the box (t_in > t_out: it misses).
std::pair<double, double> slab(const Ray& ray, const Bounds3& box) {
    double t0 = -1e300, t1 = 1e300;
    for (int a = 0; a < 3; ++a) {
        if (ray.direction[a] == 0) {
            if (ray.origin[a] < box.lo[a] || ray.origin[a] > box.hi[a]) return {1, 0};
            continue;
        }
        double u = (box.lo[a] - ray.origin[a]) / ray.direction[a];
        double v = (box.hi[a] - ray.origin[a]) / ray.direction[a];
        if (u > v) std::swap(u, v);
        t0 = std::max(t0, u);
        t1 = std::min(t1, v);
    }
    return {t0, t1};
}

TEST(KdPartition, FrontToBackOrderHoldsOnEveryRay) {
    const Bounds3 domain = domain_box();
    const std::vector<Vec3> points = random_points(4000, domain, 9);
    int rays_checked = 0;
    for (int parts : {2, 3, 5, 8}) {
        const KdPartition partition = KdPartition::balanced(samples_of(points), parts, domain);
        for (std::uint64_t seed = 1; seed <= 12; ++seed) {
            SCOPED_TRACE(seed);
            const Camera camera = random_view(domain, seed, seed % 3 == 0, seed % 4 == 1);
            const CameraFrame frame(camera, 32, 24);
            const std::vector<int> order = partition.front_to_back(frame);
            ASSERT_EQ(order.size(), static_cast<std::size_t>(parts));
            std::vector<int> rank_of(parts);
            for (int i = 0; i < parts; ++i) rank_of[order[i]] = i;
            for (int y = 0; y < 24; y += 3) {
                for (int x = 0; x < 32; x += 3) {
                    const Ray ray = frame.pixel_ray(x, y);
                    // The boxes this ray passes through (beyond the eye), by entry.
                    std::vector<std::pair<double, int>> hit;
                    for (int p = 0; p < parts; ++p) {
                        auto [t0, t1] = slab(ray, partition.box(p));
                        if (!frame.orthographic()) t0 = std::max(t0, 0.0);
                        if (t1 > t0 + 1e-9) hit.push_back({t0, p});
                    }
                    std::sort(hit.begin(), hit.end());
                    for (std::size_t i = 1; i < hit.size(); ++i) {
                        EXPECT_LT(rank_of[hit[i - 1].second], rank_of[hit[i].second])
                            << "parts " << hit[i - 1].second << " then " << hit[i].second;
                    }
                    ++rays_checked;
                }
            }
        }
    }
    EXPECT_GT(rays_checked, 1000);
}

}  // namespace
}  // namespace tr
