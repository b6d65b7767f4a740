#pragma once
// A planar 2D mesh (triangles, quads, pixels and polygons in one plane: the commonest CFD
// output) made a thin slab of wedges, so that the flow tools, which take their flow from
// tetrahedra (texture advection, spot noise, flow volumes), take the 2D mesh as the flow.
//
// The slab: each polygon fanned into triangles from its first node (a quad or pixel into two),
// each triangle extruded into a wedge from -thickness/2 to +thickness/2 along the plane's
// normal. Point fields are copied to both layers; every 2- or 3-component point field is taken
// as a vector and made tangent to the plane (a 2D vector (u, v) is (u, v, 0) first); cell
// fields are copied to each wedge of their polygon.
//
// What a flow sees on the slab's mid-plane is exactly the 2D mesh's field, linear on each of
// its triangles (quads split, not bilinear): a tet of a wedge's split meets the mid-plane where
// its edges join a bottom and a top node, at the mean of the two nodes' positions with the
// mean of their values, which is what the triangle's linear function gives there; the tet's
// linear function on its cut is then the triangle's.

#include <core/math.h>
#include <core/result.h>
#include <mesh/unstructured_mesh.h>

#include <optional>

namespace tr {

// The plane a 2D mesh lies in and the slab made of it.
struct PlanarSheet {
    Vec3 point{0.0};       // on the plane: the cells' points' bounds centre, projected
    Vec3 normal{0, 0, 1};  // unit; its largest component positive (+z for a mesh in z = c)
    double thickness = 0;  // the slab's, world units
};

// True when `mesh` has a 2D cell (triangle, quad, pixel, polygon) and every other cell is a
// vertex or a line (VTK types 1 to 4: boundary edges, probes), which the slab passes over.
bool is_surface_mesh(const UnstructuredMesh& mesh);

// The plane of a surface mesh and the slab's thickness (the median of the triangles'
// sqrt(2 area), so that a typical cell's tets are not flat). Errors (kInvalidMesh, one line):
// not a surface mesh; no cell of non-zero area; a node index out of range or a non-finite
// point; a point of a cell farther than 1e-6 of the bounds' diagonal from the plane ("not
// planar", with the distance and the point: a curved surface is not a 2D flow). Cost:
// O(cells + points).
Result<PlanarSheet> planar_sheet(const UnstructuredMesh& mesh);

// The slab of `mesh` (see above) on `sheet` (from planar_sheet): 2 x points, a wedge a
// triangle. Errors (kInvalidMesh): a node index out of range, a field whose tuples are not
// one a point (a cell). Cost: O(cells + points x fields).
Result<UnstructuredMesh> planar_slab(const UnstructuredMesh& mesh, const PlanarSheet& sheet);

}  // namespace tr
