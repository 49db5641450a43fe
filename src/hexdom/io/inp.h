// Abaqus / CalculiX input files (.inp).
#pragma once

#include <string>

#include "hexdom/mesh/mesh.h"

namespace hexdom::io {

/// Writes *NODE and one *ELEMENT block per cell type: C3D8 (hex, VTK order), C3D6 (prism: VTK
/// [a b c d e f] as a c b d f e, Abaqus numbering its first face inward), C3D4 (tet, VTK order),
/// S3/S4 for surface cells; a second-order mesh: C3D20, C3D15 (its corners as C3D6's), C3D10. An
/// element set REGION_<id> per region and EALL for all volume cells.
void write_inp(const std::string& path, const mesh::Mesh& mesh);

}  // namespace hexdom::io
