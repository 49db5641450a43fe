// Mesh containers shared by every stage.
//
// Mesh: nodes and mixed cells (triangles, quads, tetrahedra, hexahedra, wedges) in VTK node order, with
// a region id per cell. It is what the readers return and the writers take, and a volume mesh is a
// Mesh whose cells are all 3D.
// SurfaceMesh: a triangle surface with a patch id per triangle, the input of segmentation and
// parameterisation.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <string>
#include <vector>

namespace hexdom::mesh {

/// Cell types, numbered as VTK numbers them.
enum class CellType : int { Triangle = 5, Quad = 9, Tet = 10, Hex = 12, Wedge = 13 };

/// Number of nodes of a cell type (3, 4, 4, 8, 6).
int node_count(CellType type);
/// True for Tet, Hex and Wedge.
bool is_volume(CellType type);
/// "triangle", "quad", "tet", "hex", "prism".
std::string type_name(CellType type);
/// Checked conversion from a VTK cell-type number; throws std::invalid_argument for others.
CellType cell_type_from_vtk(int vtk_type);

/// Edges of a volume cell type (12, 9, 6; 0 for 2D types): the mid-edge nodes a second-order cell
/// of that type adds (mesh/cell_faces.h lists them in VTK's quadratic order).
int edge_count(CellType type);
/// VTK's number of the second-order type of a volume cell type: 25 (20-node hex), 26 (15-node
/// wedge), 24 (10-node tet); 0 for 2D types.
int second_order_vtk_type(CellType type);
/// The first-order type of VTK's 24, 25 or 26 (Tet, Hex, Wedge); throws std::invalid_argument for
/// any other number.
CellType first_order_of_vtk(int vtk_type);

/// #C by 8 cell node indices, row-major so that a row is one contiguous cell.
using CellMatrix = Eigen::Matrix<int, Eigen::Dynamic, 8, Eigen::RowMajor>;
/// #C by 12 mid-edge node indices, row-major.
using MidMatrix = Eigen::Matrix<int, Eigen::Dynamic, 12, Eigen::RowMajor>;

/// Mixed-cell mesh, VTK node order.
/// A second-order mesh (all cells volume cells, `mid` non-empty) is the first-order mesh of its
/// corners plus one node per cell edge: cell c's nodes in VTK's quadratic order (types 25, 26, 24)
/// are cells(c, 0..n-1) then mid(c, 0..e-1), the edges in cell_edges order. `types` keeps the
/// first-order type, so code that reads corners only sees the straight cells; code that builds
/// a new Mesh from another makes a first-order one, which is why the stages that move or remake
/// cells refuse a second-order input (require_first_order).
struct Mesh {
  Eigen::MatrixXd V;      ///< #V by 3 node coordinates
  CellMatrix cells;      ///< #C by 8 node indices (0-based); unused trailing slots are -1
  Eigen::VectorXi types;  ///< #C VTK cell-type numbers (see CellType)
  Eigen::VectorXi region; ///< #C region (part, block) id per cell
  MidMatrix mid;          ///< empty (first order), or #C by 12 mid-edge nodes; unused slots are -1

  int num_nodes() const { return static_cast<int>(V.rows()); }
  int num_cells() const { return static_cast<int>(cells.rows()); }
  CellType type(int c) const { return static_cast<CellType>(types(c)); }
  /// Number of cells of one type.
  int count(CellType t) const;
  bool second_order() const { return mid.rows() > 0; }
  /// The VTK number cell c is written with: types(c), or its second-order type.
  int vtk_type(int c) const { return second_order() ? second_order_vtk_type(type(c)) : types(c); }
};

/// Checks shapes, cell types and node indices (mid-edge nodes too); throws GeometryError naming
/// the first bad cell.
void validate(const Mesh& mesh);

/// The nodes of cell c in the order of its VTK type (vtk_type): corners, then mid-edge nodes of a
/// second-order mesh. Writes at most 20 entries; returns their number.
int cell_nodes(const Mesh& mesh, int c, int* nodes);

/// Throws InputError "<what> takes first-order cells: ..." when `mesh` is second order.
void require_first_order(const Mesh& mesh, const std::string& what);

/// Collects cells one at a time, then makes a Mesh.
struct MeshBuilder {
  std::vector<std::array<int, 8>> cells;
  std::vector<int> types, region;
  /// Appends a cell; `nodes` holds node_count(t) indices.
  void add(CellType t, const int* nodes, int region_id);
  Mesh finish(Eigen::MatrixXd V) const;
};

/// Triangle surface with a patch (label, CAD face) id per triangle.
struct SurfaceMesh {
  Eigen::MatrixXd V;      ///< #V by 3
  Eigen::MatrixXi F;      ///< #F by 3, counter-clockwise seen from outside
  Eigen::VectorXi patch;  ///< #F patch id per triangle
};

/// Triangles of `mesh` as a SurfaceMesh (region -> patch). Quads are split along their shorter
/// diagonal. Throws GeometryError naming the first cell if the mesh has volume cells.
SurfaceMesh to_surface(const Mesh& mesh);
/// A SurfaceMesh as a Mesh of triangle cells (patch -> region).
Mesh from_surface(const SurfaceMesh& surface);
/// The surfaces side by side in one SurfaceMesh (no vertex shared between them), in order; a
/// surface without patch ids gives its triangles patch 0.
SurfaceMesh join_surfaces(const std::vector<const SurfaceMesh*>& surfaces);
/// The surface without the vertices no triangle uses (.k files may list such nodes), the others
/// numbered in the order the triangles first use them; `s` itself when every vertex is used.
SurfaceMesh drop_unused_vertices(const SurfaceMesh& s);
/// Volume a closed triangle surface encloses (divergence theorem): positive when the triangles
/// are counter-clockwise seen from outside, negative when they face inward.
double enclosed_volume(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F);

/// Result of reading an 8-node hexahedron that may have collapsed edges.
struct DegenerateHex {
  CellType type;              ///< Hex, Wedge or Tet
  std::array<int, 8> nodes;   ///< VTK order for `type`; the first node_count(type) entries are used
};

/// Interprets an 8-node hexahedron (VTK order) whose repeated nodes collapse it into a wedge or a
/// tetrahedron, the convention of LS-DYNA *ELEMENT_SOLID and of the original HexDom's VTK output:
/// 8 distinct nodes: hex; two parallel collapsed edges of one face: wedge (orientation kept, e.g.
/// h1 h2 h3 h3 h5 h6 h7 h7 -> [h1 h3 h2 h5 h7 h6]); 4 distinct nodes: tet in order of first
/// appearance (h1 h2 h3 h4 h4 h4 h4 h4 -> [h1 h2 h3 h4]). Throws std::invalid_argument with a
/// description for any other pattern (pyramids included).
DegenerateHex classify_hex_nodes(const std::array<int, 8>& h);

/// Writes `cell` (VTK order, type `t`) as 8 LS-DYNA solid nodes: hex as is, wedge [a b c d e f] as
/// a c b b d f e e, tet [a b c d] as a b c d d d d d.
std::array<int, 8> to_hex_nodes(CellType t, const int* cell);

}  // namespace hexdom::mesh
