// Abaqus / CalculiX input files (.inp).
#pragma once

#include <string>

#include "hexdom/io/face_sets.h"
#include "hexdom/mesh/mesh.h"

namespace hexdom::io {

/// Writes *NODE and one *ELEMENT block per cell type: C3D8 (hex, VTK order), C3D6 (prism: VTK
/// [a b c d e f] as a c b d f e, Abaqus numbering its first face inward), C3D4 (tet, VTK order),
/// S3/S4 for surface cells; a second-order mesh: C3D20, C3D15 (its corners as C3D6's), C3D10. An
/// element set REGION_<id> per region and EALL for all volume cells. With `sets`, for each tag k a
/// node set Face<k> (the nodes of its faces, mid-edge nodes included) and an element-based surface
/// Face<k> ("element, S<n>" lines, S<n> the face of the element type's Abaqus numbering whose
/// corners are the face's), for *BOUNDARY and *DSLOAD on a CAD face.
void write_inp(const std::string& path, const mesh::Mesh& mesh, const FaceSets* sets = nullptr);

/// Reads the mesh of an .inp file as FEM tools write it (the subset of the keywords that hold the
/// mesh; keywords are case-blind, "**" lines are comments):
/// - *NODE: "id, x [, y [, z]]" (missing coordinates are 0); node ids are any positive integers.
/// - *ELEMENT, TYPE=..., [ELSET=name]: "id, n1, n2, ..."; an element may continue on the next lines
///   (until it has its nodes). Types C3D8*, C3D6*, C3D4*, C3D20*, C3D15*, C3D10* (any suffix: R,
///   I, H, M, ...) and S3* / S4* (surface cells, read only when the file has no solid element).
///   Orders as write_inp writes them, turned into VTK's. Cells come in the order of their ids,
///   nodes in the order of the file.
/// - *NSET / *ELSET (with GENERATE): their members must be nodes / elements or sets of the file.
/// - Region ids: when sets named REGION_<n> exist (write_inp's), an element's region is the n of the
///   set holding it; otherwise the ELSET names of the *ELEMENT lines in order of first appearance
///   are regions 1, 2, ... (0 for elements without one). EALL names no region.
/// - Any other keyword's data lines (materials, steps, loads) are skipped; *INCLUDE is refused.
/// Throws InputError "path:line: ..." for anything malformed: unknown element type, an element
/// naming a node the file does not define, a repeated node or element id, a bad number, a short
/// element, a set naming an unknown member, no node or no element.
mesh::Mesh read_inp(const std::string& path);

}  // namespace hexdom::io
