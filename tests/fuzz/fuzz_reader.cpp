// libFuzzer target for one of the readers (chosen at build time by HEXDOM_FUZZ_READER): the bytes
// become a file of the reader's extension, which is read. Every input must be answered: a mesh or
// surface that passes its own validation, or a hexdom::Error (InputError naming the file); any
// other exception, a crash or a sanitizer report is a finding.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

#include "hexdom/common/error.h"
#include "hexdom/generation/generate.h"
#include "hexdom/io/inp.h"
#include "hexdom/io/k_file.h"
#include "hexdom/io/mesh_io.h"
#include "hexdom/io/msh.h"
#include "hexdom/io/surface_formats.h"
#include "hexdom/io/vtk.h"
#include "hexdom/mesh/mesh.h"
#include "hexdom/mesh/surface_check.h"
#include "hexdom/segmentation/check_patches.h"
#include "hexdom/segmentation/read_manual_labels.h"

namespace {

#define HEXDOM_STR2(x) #x
#define HEXDOM_STR(x) HEXDOM_STR2(x)
const std::string kReader = HEXDOM_STR(HEXDOM_FUZZ_READER);

std::string extension() {
  if (kReader == "k" || kReader == "vtk" || kReader == "vtu" || kReader == "inp" || kReader == "msh" || kReader == "stl" ||
      kReader == "obj")
    return "." + kReader;
  if (kReader == "surface_checks" || kReader == "structure") return ".k";
  return ".txt";
}

const std::string& scratch() {
  static const std::string path = [] {
    const char* dir = std::getenv("HEXDOM_FUZZ_DIR");
    return std::string(dir ? dir : "/dev/shm") + "/hexdom_fuzz_" + kReader + "_" + std::to_string(getpid()) + extension();
  }();
  return path;
}

void check_surface(const hexdom::mesh::SurfaceMesh& s) {
  for (int f = 0; f < s.F.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      if (s.F(f, k) < 0 || s.F(f, k) >= s.V.rows()) std::abort();  // a reader returned a bad index
  if (s.patch.size() != s.F.rows()) std::abort();
}

// The checks of a user's surface: `hexdom mesh`'s input check (closed, manifold, oriented, not
// crossing itself) and, on a surface that passes, `hexdom check`'s polycube conditions.
void surface_checks() {
  using namespace hexdom;
  mesh::SurfaceMesh s = io::read_surface(scratch());
  check_surface(s);
  mesh::SurfaceCheckOptions o;
  o.several_solids = true;
  mesh::check_solid_surface(s, "fuzz", o);
  segmentation::check_patches(s, {});
}

// A user's polycube structure against a fixed segmented surface (a unit cube, one patch per
// face): the generation's matching and checks, at level 0.
void structure() {
  using namespace hexdom;
  static const mesh::SurfaceMesh cube = [] {
    mesh::SurfaceMesh c;
    c.V.resize(8, 3);
    c.V << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1;
    const int quads[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
    c.F.resize(12, 3);
    c.patch.resize(12);
    for (int q = 0; q < 6; ++q) {
      c.F.row(2 * q) << quads[q][0], quads[q][1], quads[q][2];
      c.F.row(2 * q + 1) << quads[q][0], quads[q][2], quads[q][3];
      c.patch(2 * q) = c.patch(2 * q + 1) = q + 1;
    }
    return c;
  }();
  const mesh::Mesh blocks = io::read_mesh(scratch());
  generation::GenerateOptions o;
  o.level = 0;
  o.threads = 1;
  mesh::validate(generation::generate(cube, blocks, o));
}

void read() {
  using namespace hexdom;
  if (kReader == "k") mesh::validate(io::read_k(scratch()).mesh);
  else if (kReader == "vtk") mesh::validate(io::read_vtk(scratch()));
  else if (kReader == "vtu") mesh::validate(io::read_vtu(scratch()));
  else if (kReader == "inp") mesh::validate(io::read_inp(scratch()));
  else if (kReader == "msh") mesh::validate(io::read_msh(scratch()));
  else if (kReader == "stl") check_surface(io::read_stl(scratch()));
  else if (kReader == "obj") check_surface(io::read_obj(scratch()));
  else if (kReader == "corner_points") io::read_corner_points(scratch());
  else if (kReader == "sharp_nodes") io::read_sharp_nodes(scratch());
  else if (kReader == "manual_labels") segmentation::read_manual_labels(scratch());
  else if (kReader == "surface_checks") surface_checks();
  else if (kReader == "structure") structure();
  else std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  {
    std::ofstream out(scratch(), std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  try {
    read();
  } catch (const hexdom::Error&) {
    // the answer a bad file gets
  }
  return 0;
}
