#pragma once
// Shirley and Tuchman's projected-tetrahedra classification (the texture-mapping paper's
// section 3.2), shared by the CPU renderer's exp-texture path and the OpenGL renderer: a tet's
// four corners projected to the image, their convex hull (3 corners: class 1, one corner inside;
// 4 corners: class 2, a quadrilateral), and the thick vertex where the ray meets the cell's
// longest chord, with its thickness and the scalar at the chord's front and back. The projected
// tet is the fan of triangles (thick, hull[e], hull[e + 1 mod num_hull]); every attribute is
// interpolated linearly in screen space across them (exact under orthographic projection, an
// approximation under perspective).
//
// Screen positions are in pixels as CameraFrame::project gives them (row 0 at the top).

#include <core/camera.h>
#include <mesh/tet_mesh.h>

#include <span>

namespace tr {

// Face planes n . x = offset (outward normals, not normalized; face k opposite vertex k) and
// the linear scalar s(x) = s0 + gradient . (x - p0) of one tet.
struct TetPlanes {
    Vec3 normals[4];
    double offsets[4];
    Vec3 p0;  // the tet's vertex 0
    double s0;
    Vec3 gradient;
};

// Planes and scalar gradient of tet `t`. `scalar` has one value per mesh point. Cost: O(1).
TetPlanes tet_planes(const TetMesh& mesh, std::span<const float> scalar, CellId t);

// A vertex of the projected tet's triangles: screen position (pixels), thickness u (world
// units), the scalar at the front and back of the ray segment there, and the ray parameter of
// the front (distance along the pixel's ray, CameraFrame::ray).
struct StVertex {
    double x, y;
    double thickness, s_front, s_back, t_front;
};

struct StProjection {
    StVertex corners[4];  // the tet's corners: thickness 0, s_front = s_back = their scalar
    StVertex thick;       // the thick vertex
    int hull[4];          // corner indices of the convex hull, in order around it
    int num_hull = 0;     // 3 (class 1) or 4 (class 2)
};

// Classifies tet `t` for `camera`. Returns false when the projection has no area or the thick
// vertex is undefined (degenerate views); then nothing is to be drawn by projection.
// Precondition: every corner is in front of a perspective eye (cells reaching behind it must be
// clipped: the CPU renderer takes its exact per-pixel path for them). Cost: O(1).
bool shirley_tuchman_projection(const TetMesh& mesh, std::span<const float> scalar, CellId t,
                                const TetPlanes& planes, const CameraFrame& camera,
                                StProjection& out);

}  // namespace tr
