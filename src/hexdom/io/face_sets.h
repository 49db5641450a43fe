// Boundary faces named for the solvers' loads and supports: each tagged with the CAD face it lies
// on, the writers name the sets as FreeCAD names faces (Face1, Face2, ...).
#pragma once

#include <map>
#include <vector>

#include "hexdom/mesh/cell_faces.h"

namespace hexdom::io {

struct FaceSets {
  std::vector<mesh::BoundaryFace> faces;  ///< boundary faces of the mesh written
  std::vector<int> tag;                   ///< per face: its CAD face id (>= 1), or < 1 for none
  /// Per tag >= 1: the nodes (0-based, increasing) on that CAD face, the node sets (*NSET, FreeCAD's
  /// node groups): the nodes of its faces (mid-edge nodes included), less those known to lie on
  /// other CAD faces only (face_sets' node_faces).
  std::map<int, std::vector<int>> nodes;
  /// Per face: 1 when its corners' CAD faces are all known (node_faces) and share none, so that it
  /// crosses a CAD edge (FreeCAD's face loads, which take the mesh faces with every node on the
  /// CAD face, leave it out); 0 otherwise.
  std::vector<char> across;
  bool empty() const { return faces.empty(); }
  /// The faces (indices into `faces`) of each tag >= 1, by increasing tag.
  std::map<int, std::vector<size_t>> by_tag() const;
};

/// The boundary faces of `mesh` (mesh::boundary_faces), each tagged with the CAD face it lies on,
/// and the nodes of each CAD face. Empty when `surface` has no triangles.
/// `node_faces`, when given (#V or fewer rows; the B-rep snap's SnapResult::faces), holds the CAD
/// faces each boundary node lies on (empty: not known; a second-order mesh's mid-edge nodes are
/// not listed). A face whose corners are all known takes the one CAD face they share (of several,
/// the nearest triangle's if it is one of them, else the lowest); a node known to lie on other
/// faces, and a mid-edge node whose two corners share none of them, is not in a face's node set.
/// Otherwise (a face crossing a sharp curve, as the overlay path may let one, or no node_faces) a
/// face takes the patch (CAD face id) of the triangle of `surface` nearest its centre: for a mesh
/// made from a tessellation with CAD face ids, the CAD face it lies on.
FaceSets face_sets(const mesh::Mesh& mesh, const mesh::SurfaceMesh& surface,
                   const std::vector<std::vector<int>>& node_faces = {});

/// The nodes of tag `tag` (0-based, increasing): sets.nodes' when it has the tag, else every node of
/// the faces tagged so (sets made by hand).
std::vector<int> set_nodes(const mesh::Mesh& mesh, const FaceSets& sets, int tag);

}  // namespace hexdom::io
