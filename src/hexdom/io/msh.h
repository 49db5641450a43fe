// Gmsh .msh files: MSH 4.1 and 2.2, ASCII and binary (reading); MSH 4.1 ASCII (writing).
#pragma once

#include <string>

#include "hexdom/io/face_sets.h"
#include "hexdom/mesh/mesh.h"

namespace hexdom::io {

/// Reads a Gmsh mesh file, MSH 4.1 or 2.2, ASCII or binary (little- or big-endian, as the check int
/// after the format line says; in 4.1 a size_t is as wide as the format line's data size, 4 or 8).
///
/// Sections read: $MeshFormat (first), $Entities (4.1), $Nodes, $Elements; $Nodes comes before
/// $Elements, $Entities before both. Every other section ($PhysicalNames, $NodeData, $Periodic,
/// $PartitionedEntities, ...) is skipped up to its $End line. Node tags may be sparse and in any
/// order; 4.1 parametric coordinates are skipped. Every node of the file is a node of the mesh, in
/// file order.
///
/// Elements: Gmsh types 4 (tet), 5 (hex), 6 (prism), 11 (tet10), 17 (hex20), 18 (prism15) are the
/// volume cells; 2 (triangle) and 3 (quad) the surface cells. When the file has any volume cell,
/// the mesh holds the volume cells only (points, lines and 2D elements of the file are skipped);
/// otherwise it is the surface of its triangles and quads. Node order becomes VTK's: the prism is
/// Gmsh's mirror of VTK's wedge (its first triangle turns toward the second), so its nodes 1, 2 and
/// 4, 5 are swapped; second-order nodes follow their edges.
///
/// Region id of a cell: the first physical group of its entity (4.1: of the entity in $Entities;
/// 2.2: the element's first tag), or, when that entity is in no physical group, the entity's own
/// tag (2.2: the second tag; 0 when the element has fewer tags). A 2.2 element that repeats the
/// element before it (same type, entity and nodes: how Gmsh writes an element of several physical
/// groups) is read once, with the first group.
///
/// Throws InputError "path:line: ..." for anything malformed or unsupported, naming the element or
/// node tag: another format or version, a count larger than the file, data that ends early
/// ("truncated?"), a missing $End line, a duplicate node tag, an element whose node tag is not in
/// $Nodes, an unknown element type, another 3D type (pyramids, hex27, prism18, third order, ...), a
/// second-order 2D element in a surface mesh, first- and second-order cells in one mesh.
mesh::Mesh read_msh(const std::string& path);

/// Writes MSH 4.1 ASCII, as Gmsh writes it: the cells of region r in volume entity r, physical group
/// (3, r) named "Region<r>" (every id shifted to start at 1 when a region is below 1, the names
/// keeping the ids); Gmsh types 4, 5, 6 (11, 17,
/// 18 for a second-order mesh, in Gmsh's node order). With `sets`, the boundary faces tagged k as
/// triangles / quads (6-node triangles, 8-node quads for a second-order mesh) in surface entity k,
/// physical group (2, k) named "Face<k>", oriented out of the mesh. A mesh of 2D cells writes them in
/// surface entities, one per region, physical groups "Region<r>". Every node is in one block of the
/// first entity. Cells keep their order (a new element block wherever the region or the type
/// changes), so cell c has element tag c + 1; the faces' tags follow.
void write_msh(const std::string& path, const mesh::Mesh& mesh, const FaceSets* sets = nullptr);

}  // namespace hexdom::io
