// A face triangulated by hexdom itself, for the faces where BRepMesh gave no triangulation or one
// that cannot be used (cad/tessellate_merge.h). Internal to hexdom_cad: only cad/*.cpp include it.
//
// Method: the face's wires become loops of its edges' nodes (the nodes the merged surface already
// has for each edge, so the face meets its neighbours node for node; an edge that has none yet is
// discretised here along its 3D curve). Each node gets (u, v) from its edge's curve on the face,
// or, where that curve strays from the 3D edge (a bad pcurve), from projecting the node onto the
// surface. A periodic face bounded by two closed wires and no seam edge gets a seam from one wire
// to the other. The loops are triangulated in (u, v) scaled to the surface's metric by ear
// clipping (mesh/triangulate_polygon.h), then edges longer than the target size are split at
// their (u, v) midpoints and edges flipped towards larger angles; the remesher does the rest.
#pragma once

#include "hexdom/cad/tessellate_merge.h"

namespace hexdom::cad {

/// Triangulates face `fi` (0-based in w.faces) and appends its triangles (counter-clockwise seen
/// from outside, as the face's orientation in the solid says) and its new vertices to `out`.
/// Throws MeshingError "source: FaceN cannot be triangulated: <reason>" when its boundary cannot be
/// laid out in its parameters (a wire off its surface, wires that cross, a wire whose edges do not
/// join, wires around a periodic surface without a seam that cannot be paired).
void triangulate_face(const WorkShape& w, int fi, const Sizes& z, Merged& out);

}  // namespace hexdom::cad
