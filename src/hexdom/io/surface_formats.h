// Triangle surface formats: STL (ASCII and binary) and Wavefront OBJ.
#pragma once

#include <string>

#include "hexdom/mesh/mesh.h"

namespace hexdom::io {

/// Reads an ASCII or binary STL. Vertices with identical coordinates are merged; each "solid" of an
/// ASCII file is its own patch (1, 2, ...). Throws InputError for truncated or malformed files.
mesh::SurfaceMesh read_stl(const std::string& path);
/// Writes a binary STL (patch ids are not kept).
void write_stl(const std::string& path, const mesh::SurfaceMesh& surface);

/// Reads "v" and "f" lines (v, v/vt, v//vn, v/vt/vn, negative indices; polygons are fanned);
/// each "g"/"o" group is its own patch: "patch_<id>" keeps <id>, other names are
/// numbered 1, 2, ... in order of appearance; faces before any group get patch 0.
mesh::SurfaceMesh read_obj(const std::string& path);
/// Writes vertices and faces, one group "patch_<id>" per patch.
void write_obj(const std::string& path, const mesh::SurfaceMesh& surface);

}  // namespace hexdom::io
