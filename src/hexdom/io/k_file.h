// LS-DYNA keyword files (.k) as the original HexDom pipeline and LS-PrePost use them.
#pragma once

#include <string>
#include <vector>

#include "hexdom/io/face_sets.h"
#include "hexdom/mesh/mesh.h"

namespace hexdom::io {

/// Contents of a .k file. Node and element ids are kept so that messages and round trips can name
/// them; the mesh itself is 0-based.
struct KFile {
  mesh::Mesh mesh;           ///< shells as triangles/quads, solids as hex/wedge/tet; region = part id
  Eigen::VectorXi node_ids;  ///< #V LS-DYNA node id of each row of mesh.V
  Eigen::VectorXi element_ids;  ///< #C LS-DYNA element id of each cell
};

/// Reads *NODE, *ELEMENT_SHELL (triangle when n4 = n3 or n4 = 0) and *ELEMENT_SOLID (8 nodes;
/// collapsed edges give prisms and tetrahedra, see mesh::classify_hex_nodes; in its ten-node format,
/// "eid pid" and then a card of 10 node ids, a 10-node tetrahedron, or an 8-node solid when the last
/// two are 0), and *ELEMENT_SOLID_H20 (20-node hexahedra: "eid pid", then two cards of 10 node ids).
/// A file with 10- or 20-node solids gives a second-order mesh (LS-DYNA's node orders are VTK's);
/// it may not mix them with 8-node solids or shells (io::CellAssembly's checks). Fields may be
/// comma-separated, blank-separated or fixed width (8-character integers, 16-character reals);
/// lines starting with '$' are comments; *PART and the other LS-DYNA keywords are skipped. Node ids
/// are mapped, not assumed to be 1..N, and nodes no element uses are kept.
/// Throws InputError "path:line: ..." for a malformed line, an unknown keyword, a non-finite
/// coordinate, a duplicate node id, an element naming a missing node, or a file with no nodes.
KFile read_k(const std::string& path);

/// Writes nodes (ids 1..N), 2D cells as *ELEMENT_SHELL (triangles repeat n3) and 3D cells as
/// *ELEMENT_SOLID (prism a c b b d f e e, tet a b c d d d d d), part id = region;
/// elements in fixed width, nodes comma-separated with full double precision. A second-order mesh:
/// 20-node hexes as *ELEMENT_SOLID_H20, 10-node tets in *ELEMENT_SOLID's ten-node format; LS-DYNA
/// has no 15-node pentahedron, so a mesh with wedges is refused (InputError naming the first, no file). With `faces` (not
/// empty), a *SET_SEGMENT_TITLE per tag k >= 1 titled Face<k> (set id k): its boundary faces as
/// segments, outward (triangles repeat n3).
void write_k(const std::string& path, const mesh::Mesh& mesh, const FaceSets* faces = nullptr);

/// One entry of the original PrismGen/TetGen corner file `<input>_Output_CornerPoints.txt`.
struct CornerPoint {
  int vertex;        ///< 0-based vertex index in the matching surface
  double p[3];       ///< position in the parametric domain
};
/// Reads "vertexIndex px py pz" lines. Throws InputError on malformed lines.
std::vector<CornerPoint> read_corner_points(const std::string& path);

/// Reads the original quality step's sharp-feature file: the last integer of each non-empty line is
/// a 0-based node index. Throws InputError on a line without an integer.
std::vector<int> read_sharp_nodes(const std::string& path);

}  // namespace hexdom::io
