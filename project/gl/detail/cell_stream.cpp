#include <core/parallel.h>
#include <project/gl/detail/cell_stream.h>
#include <project/tet_projection.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <limits>

namespace tr::gl::detail {

bool needs_exact(const TetMesh& mesh, CellId t, const CameraFrame& camera) {
    const double guard = kExactGuard * (camera.width() + camera.height());
    for (PointId p : mesh.tet(t)) {
        const Vec3 q = camera.project(mesh.point(p));
        if (q.z <= 0) return true;
        if (std::abs(q.x - 0.5 * camera.width()) > guard) return true;
        if (std::abs(q.y - 0.5 * camera.height()) > guard) return true;
    }
    return false;
}

// The part of the tet in front of the eye projects to the convex hull of its front corners'
// images and of the directions (right, up parts) of the points where it meets the eye's plane:
// a direction with a positive right part makes the rectangle reach the image's right edge, and
// so on; one with neither part (the eye on the tet's boundary or inside it) the whole image.
bool exact_cell(const TetMesh& mesh, std::span<const float> scalar, CellId t, std::size_t index,
                const CameraFrame& camera, ExactCell& out) {
    const Vec3& eye = camera.eye();
    const Tet& tet = mesh.tet(t);
    Vec3 d[4];
    double z[4];
    constexpr double kInf = std::numeric_limits<double>::infinity();
    double x0 = kInf, y0 = kInf, x1 = -kInf, y1 = -kInf;
    bool front = false;
    for (int k = 0; k < 4; ++k) {
        d[k] = mesh.point(tet[k]) - eye;
        z[k] = glm::dot(d[k], camera.forward());
        if (z[k] > 0) {
            const Vec3 q = camera.project(mesh.point(tet[k]));
            x0 = std::min(x0, q.x), x1 = std::max(x1, q.x);
            y0 = std::min(y0, q.y), y1 = std::max(y1, q.y);
            front = true;
        }
    }
    if (!front) return false;
    for (int a = 0; a < 4; ++a) {
        if (z[a] > 0) continue;
        for (int b = 0; b < 4; ++b) {
            if (!(z[b] > 0)) continue;
            const Vec3 q = d[a] + (d[b] - d[a]) * (-z[a] / (z[b] - z[a]));
            const double right = glm::dot(q, camera.right()), up = glm::dot(q, camera.up());
            if (right == 0 && up == 0) x0 = y0 = -kInf, x1 = y1 = kInf;
            if (right > 0) x1 = kInf;
            if (right < 0) x0 = -kInf;
            if (up > 0) y0 = -kInf;  // image rows go down
            if (up < 0) y1 = kInf;
        }
    }
    const double w = camera.width(), h = camera.height();
    // Pixels whose centres may be inside, padded by a pixel (the fragment shader decides).
    x0 = std::clamp(std::floor(x0) - 1.0, 0.0, w), x1 = std::clamp(std::ceil(x1) + 1.0, 0.0, w);
    y0 = std::clamp(std::floor(y0) - 1.0, 0.0, h), y1 = std::clamp(std::ceil(y1) + 1.0, 0.0, h);
    if (!(x1 > x0) || !(y1 > y0)) return false;
    const TetPlanes planes = tet_planes(mesh, scalar, t);
    for (int k = 0; k < 4; ++k) {
        const double len = glm::length(planes.normals[k]);
        if (!(len > 0)) return false;
        const Vec3 n = planes.normals[k] / len;
        out.planes[4 * k + 0] = static_cast<float>(n.x);
        out.planes[4 * k + 1] = static_cast<float>(n.y);
        out.planes[4 * k + 2] = static_cast<float>(n.z);
        out.planes[4 * k + 3] =
            static_cast<float>((planes.offsets[k] - glm::dot(planes.normals[k], eye)) / len);
    }
    out.index = index;
    out.rect[0] = static_cast<float>(2 * x0 / w - 1);
    out.rect[1] = static_cast<float>(1 - 2 * y1 / h);
    out.rect[2] = static_cast<float>(2 * x1 / w - 1);
    out.rect[3] = static_cast<float>(1 - 2 * y0 / h);
    out.scalar[0] = static_cast<float>(planes.gradient.x);
    out.scalar[1] = static_cast<float>(planes.gradient.y);
    out.scalar[2] = static_cast<float>(planes.gradient.z);
    out.scalar[3] = static_cast<float>(planes.s0 + glm::dot(planes.gradient, eye - planes.p0));
    return true;
}

void classify_cells(const TetMesh& mesh, std::span<const float> scalar,
                    std::span<const CellId> order, const CameraFrame& camera, CellStream& stream) {
    const std::size_t n = order.size();
    stream.vertices.resize(n * kVerticesPerCell * kFloatsPerVertex);
    stream.exact_flags.assign(n, 0);
    stream.exact_cells.clear();
    std::atomic<std::size_t> drawn{0};
    const bool orthographic = camera.orthographic();
    parallel_for_chunks(0, n, 2048, [&](std::size_t begin, std::size_t end) {
        std::size_t local = 0;
        for (std::size_t i = begin; i < end; ++i) {
            float* out = &stream.vertices[i * kVerticesPerCell * kFloatsPerVertex];
            const CellId t = order[i];
            // Cells reaching behind the eye (or too close to it to project) are drawn exactly
            // per pixel instead, in their place in the order.
            const bool exact = !orthographic && needs_exact(mesh, t, camera);
            stream.exact_flags[i] = exact ? 1 : 0;
            bool ok = !exact;
            StProjection st;
            if (ok) {
                const TetPlanes planes = tet_planes(mesh, scalar, t);
                ok = shirley_tuchman_projection(mesh, scalar, t, planes, camera, st);
            }
            if (!ok) {
                std::memset(out, 0, kVerticesPerCell * kFloatsPerVertex * sizeof(float));
                continue;
            }
            ++local;
            auto put = [&](int slot, const StVertex& v) {
                float* o = out + slot * kFloatsPerVertex;
                o[0] = static_cast<float>(v.x);
                o[1] = static_cast<float>(v.y);
                o[2] = static_cast<float>(v.thickness);
                o[3] = static_cast<float>(v.s_front);
                o[4] = static_cast<float>(v.s_back);
                o[5] = static_cast<float>(v.t_front);
            };
            put(0, st.thick);
            for (int k = 0; k < 4; ++k)
                put(1 + k, st.corners[st.hull[std::min(k, st.num_hull - 1)]]);
        }
        drawn += local;
    });
    for (std::size_t i = 0; i < n; ++i) {
        ExactCell cell;
        if (stream.exact_flags[i] && exact_cell(mesh, scalar, order[i], i, camera, cell))
            stream.exact_cells.push_back(cell);
    }
    stream.projected = drawn.load();
}

}  // namespace tr::gl::detail
