#include <project/tet_projection.h>

#include <algorithm>

namespace tr {
namespace {

double cross2(double ax, double ay, double bx, double by, double cx, double cy) {
    return (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
}

}  // namespace

TetPlanes tet_planes(const TetMesh& mesh, std::span<const float> scalar, CellId t) {
    const Tet& v = mesh.tet(t);
    TetPlanes planes;
    for (int k = 0; k < 4; ++k) {
        const Vec3& a = mesh.point(v[kTetFaceVertices[k][0]]);
        planes.normals[k] = glm::cross(mesh.point(v[kTetFaceVertices[k][1]]) - a,
                                       mesh.point(v[kTetFaceVertices[k][2]]) - a);
        planes.offsets[k] = glm::dot(planes.normals[k], a);
    }
    planes.p0 = mesh.point(v[0]);
    planes.s0 = scalar[v[0]];
    const glm::dmat3 edges(mesh.point(v[1]) - planes.p0, mesh.point(v[2]) - planes.p0,
                           mesh.point(v[3]) - planes.p0);
    const Vec3 ds(scalar[v[1]] - planes.s0, scalar[v[2]] - planes.s0, scalar[v[3]] - planes.s0);
    planes.gradient = glm::inverse(glm::transpose(edges)) * ds;
    return planes;
}

bool shirley_tuchman_projection(const TetMesh& mesh, std::span<const float> scalar, CellId t,
                                const TetPlanes& planes, const CameraFrame& camera,
                                StProjection& out) {
    const Tet& v = mesh.tet(t);
    StVertex* corners = out.corners;
    for (int k = 0; k < 4; ++k) {
        const Vec3& world = mesh.point(v[k]);
        const Vec3 q = camera.project(world);
        const Ray r = camera.ray(q.x, q.y);
        const double tk = glm::dot(world - r.origin, r.direction);
        corners[k] = {q.x, q.y, 0.0, scalar[v[k]], scalar[v[k]], tk};
    }
    // Convex hull of the four projected corners (monotone chain).
    int* hull = out.hull;
    int n = 0;
    {
        int order4[4] = {0, 1, 2, 3};
        std::sort(order4, order4 + 4, [&](int a, int c) {
            return corners[a].x != corners[c].x ? corners[a].x < corners[c].x
                                                : corners[a].y < corners[c].y;
        });
        int chain[8], m = 0;
        for (int i = 0; i < 4; ++i) {
            while (m >= 2 && cross2(corners[chain[m - 2]].x, corners[chain[m - 2]].y,
                                    corners[chain[m - 1]].x, corners[chain[m - 1]].y,
                                    corners[order4[i]].x, corners[order4[i]].y) <= 0) {
                --m;
            }
            chain[m++] = order4[i];
        }
        for (int i = 2, lower = m + 1; i >= 0; --i) {
            while (m >= lower && cross2(corners[chain[m - 2]].x, corners[chain[m - 2]].y,
                                        corners[chain[m - 1]].x, corners[chain[m - 1]].y,
                                        corners[order4[i]].x, corners[order4[i]].y) <= 0) {
                --m;
            }
            chain[m++] = order4[i];
        }
        n = m - 1;
        for (int i = 0; i < n && i < 4; ++i) hull[i] = chain[i];
    }
    out.num_hull = n;
    if (n < 3) return false;  // no area on screen
    // The thick vertex: where the ray meets the cell's longest chord. Class 1 (a corner
    // projects inside the other three): that corner and the opposite face. Class 2 (a
    // quadrilateral): the two opposite edges whose projections are its diagonals.
    double ta = 0, tb = 0, tx = 0, ty = 0;
    Ray thick_ray;
    if (n == 3) {
        int inner = 0;
        for (int k = 0; k < 4; ++k) {
            if (k != hull[0] && k != hull[1] && k != hull[2]) inner = k;
        }
        tx = corners[inner].x, ty = corners[inner].y;
        thick_ray = camera.ray(tx, ty);
        ta = glm::dot(mesh.point(v[inner]) - thick_ray.origin, thick_ray.direction);
        const double den = glm::dot(planes.normals[inner], thick_ray.direction);
        if (den == 0) return false;
        tb = (planes.offsets[inner] - glm::dot(planes.normals[inner], thick_ray.origin)) / den;
    } else {
        const StVertex &a = corners[hull[0]], &c = corners[hull[2]];
        const StVertex &b2 = corners[hull[1]], &d = corners[hull[3]];
        const double den = (c.x - a.x) * (d.y - b2.y) - (c.y - a.y) * (d.x - b2.x);
        if (den == 0) return false;
        const double u = ((b2.x - a.x) * (d.y - b2.y) - (b2.y - a.y) * (d.x - b2.x)) / den;
        tx = a.x + u * (c.x - a.x), ty = a.y + u * (c.y - a.y);
        thick_ray = camera.ray(tx, ty);
        // Ray parameter of the closest approach to each 3D edge.
        auto on_line = [&](const Vec3& p, const Vec3& q) {
            const Vec3 e = q - p, w0 = thick_ray.origin - p;
            const double A = glm::dot(thick_ray.direction, thick_ray.direction);
            const double B = glm::dot(thick_ray.direction, e);
            const double C = glm::dot(e, e);
            const double denom = A * C - B * B;
            if (denom == 0) return glm::dot(p - thick_ray.origin, thick_ray.direction);
            return (B * glm::dot(e, w0) - C * glm::dot(thick_ray.direction, w0)) / denom;
        };
        ta = on_line(mesh.point(v[hull[0]]), mesh.point(v[hull[2]]));
        tb = on_line(mesh.point(v[hull[1]]), mesh.point(v[hull[3]]));
    }
    const double t_front = std::min(ta, tb), t_back = std::max(ta, tb);
    auto scalar_at = [&](double tp) {
        return planes.s0 +
               glm::dot(planes.gradient, thick_ray.origin + tp * thick_ray.direction - planes.p0);
    };
    out.thick = {tx, ty, t_back - t_front, scalar_at(t_front), scalar_at(t_back), t_front};
    return true;
}

}  // namespace tr
