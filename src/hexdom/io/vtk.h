// VTK files: legacy (.vtk, ASCII or binary, versions 2 to 5.1) and XML unstructured grids (.vtu).
#pragma once

#include <string>

#include "hexdom/io/face_sets.h"
#include "hexdom/mesh/mesh.h"

namespace hexdom::io {

/// Reads a legacy VTK UNSTRUCTURED_GRID (or POLYDATA of triangles and quads), ASCII or binary, with
/// CELLS in the classic layout or the 5.1 OFFSETS/CONNECTIVITY layout. Cell types 5, 9, 10, 12 and
/// 13 are read; a hexahedron (12) with repeated nodes becomes a prism or a tet (as the original
/// HexDom wrote them). Second-order volume cells (25 hex20, 26 wedge15, 24 tet10) give a
/// second-order mesh; a file that mixes them with first-order cells is refused. Region ids come from the cell scalars or field array named "region",
/// "BlockId", "RegionId", "gmsh:physical" or "medit:ref" (the first present), else 0.
/// Throws InputError "path:line: ..." for anything malformed or unsupported.
mesh::Mesh read_vtk(const std::string& path);

/// Reads a VTK XML UnstructuredGrid (.vtu) as VTK and meshio write it: DataArrays in ascii, binary
/// (base64, inline) or appended (raw or base64) format, header_type UInt32 or UInt64, either byte
/// order, uncompressed or compressed with vtkZLibDataCompressor; every Piece (their points and cells
/// one after the other). Cell types, collapsed hexahedra, second order and region ids as read_vtk
/// (a cell array with one of its region names). With volume cells, the triangles and quads beside
/// them (first or second order: boundary faces, as write_vtu adds them) are left out; without, the
/// triangles and quads are the mesh. Throws InputError "path:line: ..." naming the element or array
/// for anything malformed or unsupported (other compressors, polyhedra).
mesh::Mesh read_vtu(const std::string& path);

/// Writes a legacy VTK 4.2 UNSTRUCTURED_GRID with native cell types (a second-order mesh's: 25, 26,
/// 24) and an int cell array "region".
void write_vtk(const std::string& path, const mesh::Mesh& mesh, bool binary = false);

/// Writes a VTK XML UnstructuredGrid (.vtu) with base64-encoded binary arrays and "region"; cell
/// types as write_vtk. With `faces` (not empty), its boundary faces follow the cells as triangles
/// and quads (second order: VTK 22 and 23, mid-edge nodes as mesh::face_nodes), region 0, and a
/// cell array "face_id" gives each its tag (the CAD face; 0 for the volume cells).
void write_vtu(const std::string& path, const mesh::Mesh& mesh, const FaceSets* faces = nullptr);

}  // namespace hexdom::io
