// Pillowing: one layer of cells over (part of) the boundary of a volume mesh, so that no cell keeps
// two faces on the boundary.
#pragma once

#include <vector>

#include "hexdom/mesh/mesh.h"
#include "hexdom/optimize/node_kinds.h"

namespace hexdom::optimize {

/// Adds one layer of cells along the boundary (quads -> hexes, triangles -> prisms) and moves the
/// old boundary nodes inward; the new boundary nodes keep the old boundary positions. Returns the
/// new mesh; `old_to_new` (#V of the input) receives each old boundary node's new boundary copy
/// (-1 for interior nodes).
mesh::Mesh pillow(const mesh::Mesh& mesh, double depth, std::vector<int>* old_to_new = nullptr);

/// \overload Pillows only the boundary faces f with faces[f] != 0 (#faces of
/// mesh::boundary_faces(mesh), in its order): a layer over part of the boundary. An old node on the
/// edge of that part (it also lies on a face left out) moves inward along the faces left out
/// (their tangent plane, or the line where two of them meet), so the layer's side faces lie on them
/// and the old mesh stays conforming; with a curved face left out, it ends off that face by the
/// order of depth squared times the curvature (project it back). Throws GeometryError naming the
/// node where no such move exists: at a corner of three faces left out, or where the faces left
/// out do not lie ahead of the layer (a reflex edge).
mesh::Mesh pillow(const mesh::Mesh& mesh, double depth, const std::vector<char>& faces,
                  std::vector<int>* old_to_new = nullptr);

/// The layer over the boundary faces f with (*mask)[f] (all of them when `mask` is null), as
/// pillow(). Each old boundary node moves inward by its layer thickness x its scale (`node_scale`,
/// #V of the input, 1 for every node when null): depth x its shortest edge on the layer's faces,
/// or, when `share` > 0 and that is thicker, `share` x its shortest edge off them (the height of
/// the cells under the layer; its shortest layer edge where it has no other) but not more than
/// that shortest layer edge, so that a layer cell is
/// not needle-thin against its own face nor against the cell under it. Where a cell valid before
/// comes out inverted, the scale of its moved nodes is halved and the layer made again (a bounded
/// number of times).
mesh::Mesh pillow_faces(const mesh::Mesh& mesh, double depth, const std::vector<char>* mask, std::vector<int>* old_to_new,
                        const std::vector<double>* node_scale = nullptr, double share = 0);

/// Boundary faces (#faces of kinds.faces, flags) for a layer where a polycube edge lies on a smooth
/// surface: the smooth regions in which some cell has two faces meeting at an edge (its dihedral
/// there is near 180 degrees, which no node placement mends), grown across reflex edges (a layer
/// cannot end at one). Empty when no region has such a cell, or when the layer would cover every
/// face.
std::vector<char> smooth_layer_faces(const mesh::Mesh& mesh, const NodeKinds& kinds);

}  // namespace hexdom::optimize
