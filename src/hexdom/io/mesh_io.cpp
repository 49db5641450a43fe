#include "hexdom/io/mesh_io.h"

#include <fstream>

#include "hexdom/common/error.h"
#include "hexdom/io/inp.h"
#include "hexdom/io/k_file.h"
#include "hexdom/io/msh.h"
#include "hexdom/io/surface_formats.h"
#include "hexdom/io/text.h"
#include "hexdom/io/vtk.h"

namespace hexdom::io {

Format format_of(const std::string& path) {
  const std::string e = extension(path);
  if (e == "k" || e == "key" || e == "dyn") return Format::K;
  if (e == "vtk") return Format::Vtk;
  if (e == "vtu") return Format::Vtu;
  if (e == "inp") return Format::Inp;
  if (e == "stl") return Format::Stl;
  if (e == "obj") return Format::Obj;
  if (e == "msh") return Format::Msh;
  throw InputError(path, 0, "unknown file format '." + e + "' (expected .k, .vtk, .vtu, .inp, .msh, .stl or .obj)");
}

Format output_format_of(const std::string& path) { return format_of(path); }

namespace {
// For .k and .vtk: the format the first non-blank character says ('$' or '*' for keyword files,
// '#' for legacy VTK), else the extension's.
Format sniff(const std::string& path, Format by_ext) {
  if (by_ext != Format::K && by_ext != Format::Vtk) return by_ext;
  std::ifstream in(path, std::ios::binary);
  char c = 0;
  while (in.get(c) && std::isspace(static_cast<unsigned char>(c))) {}
  if (c == '$' || c == '*') return Format::K;
  if (c == '#') return Format::Vtk;
  return by_ext;
}
}  // namespace

mesh::Mesh read_mesh(const std::string& path) {
  switch (sniff(path, format_of(path))) {
    case Format::K: return read_k(path).mesh;
    case Format::Vtk: return read_vtk(path);
    case Format::Stl: return mesh::from_surface(read_stl(path));
    case Format::Obj: return mesh::from_surface(read_obj(path));
    case Format::Vtu: return read_vtu(path);
    case Format::Inp: return read_inp(path);
    case Format::Msh: return read_msh(path);
    default: throw InputError(path, 0, "reading ." + extension(path) + " files is not supported (read .k, .vtk, .vtu, .inp, .msh, .stl or .obj)");
  }
}

mesh::SurfaceMesh read_surface(const std::string& path) {
  Format f = sniff(path, format_of(path));
  if (f == Format::Stl) return read_stl(path);
  if (f == Format::Obj) return read_obj(path);
  mesh::Mesh m = read_mesh(path);
  try {
    return mesh::to_surface(m);
  } catch (const GeometryError& e) {
    throw InputError(path, 0, std::string("not a surface: ") + e.what());
  }
}

void write_mesh(const std::string& path, const mesh::Mesh& m, const WriteOptions& options) {
  switch (output_format_of(path)) {
    case Format::K:
      write_k(path, m, options.face_sets.empty() ? nullptr : &options.face_sets);
      break;
    case Format::Vtk: write_vtk(path, m, options.binary); break;
    case Format::Vtu: write_vtu(path, m, options.face_sets.empty() ? nullptr : &options.face_sets); break;
    case Format::Inp: write_inp(path, m, options.face_sets.empty() ? nullptr : &options.face_sets); break;
    case Format::Msh: write_msh(path, m, options.face_sets.empty() ? nullptr : &options.face_sets); break;
    case Format::Stl:
    case Format::Obj: {
      mesh::SurfaceMesh s;
      try {
        s = mesh::to_surface(m);
      } catch (const GeometryError& e) {
        throw InputError(path, 0, std::string("cannot write volume cells to a surface format: ") + e.what());
      }
      if (format_of(path) == Format::Stl) write_stl(path, s);
      else write_obj(path, s);
      break;
    }
  }
}

}  // namespace hexdom::io
