// `--crease-angle DEG`: edges whose dihedral angle exceeds DEG become
// infinitely sharp creases, so a CAD part (fandisk's 700-odd feature edges)
// keeps its edges without a hand-written tag file.
//
// The dihedral angle of an edge is the angle between the normals of the two
// faces that share it: 0 where the surface is flat across the edge, 90 on a
// cube's edge. It is measured between the file's polygons (Newell normals),
// so the diagonals that triangulating a polygon adds are never creased, and
// boundary edges (sharp already by the boundary rule) are left alone. The
// vertex rules follow from the sharp edges as for any tags (Pulli & Lounsbery,
// "Hierarchical Editing and Rendering of Subdivision Surfaces" §2.4,
// OpenSubdiv's Sdc): an end of one sharp edge is a dart, a vertex on two a
// crease vertex, on three or more a corner.
#pragma once

#include "core/mesh/base_mesh.h"
#include "core/mesh/polygon_soup.h"
#include "core/util/status.h"

namespace tessera {

// Creases the edges of `mesh` (built from `soup`, the same vertex numbers)
// whose dihedral angle exceeds `degrees` (0 to 180). Returns how many.
Expected<int> creaseByDihedralAngle(const PolygonSoup& soup, double degrees, BaseMesh& mesh);

}  // namespace tessera
