// Reading and writing any supported format, chosen by file extension (and, for .k and .vtk, checked
// against the file's first bytes, since the paper's data holds a .k file named .vtk).
#pragma once

#include <string>

#include "hexdom/io/face_sets.h"
#include "hexdom/mesh/mesh.h"

namespace hexdom::io {

/// Formats: k, vtk, vtu, inp, msh (Gmsh), stl, obj (read and write).
enum class Format { K, Vtk, Vtu, Inp, Stl, Obj, Msh };

/// Format from the extension; throws InputError naming the path for an unknown one.
Format format_of(const std::string& path);
/// Format of an output file (every readable format is written too): format_of, called by the
/// commands so that an unknown output is refused before any work.
Format output_format_of(const std::string& path);

/// Reads a mesh of any readable format (STL and OBJ surfaces come back as triangle cells).
mesh::Mesh read_mesh(const std::string& path);
/// Reads a triangle surface (k shells, stl, obj, vtk or msh triangles/quads); quads are split.
mesh::SurfaceMesh read_surface(const std::string& path);

struct WriteOptions {
  bool binary = false;  ///< legacy VTK only
  /// .inp and .msh: the boundary faces on each CAD face k as a set named Face<k> (.inp: node set and
  /// element surface; .msh: physical group of surface elements); .vtu: the boundary faces as
  /// triangle / quad cells after the volume cells, with a "face_id" cell array (write_vtu); .k: a
  /// segment set Face<k> per CAD face (write_k).
  FaceSets face_sets;
};
/// Writes a mesh in the format of the extension. STL and OBJ take surface cells only; a second-order
/// mesh goes to .vtk, .vtu and .inp (.k refuses it with an InputError naming the file). Writing .msh
/// is not supported: an InputError names the file.
void write_mesh(const std::string& path, const mesh::Mesh& mesh, const WriteOptions& options = {});

}  // namespace hexdom::io
