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
#include "hexdom/io/inp.h"
#include "hexdom/io/k_file.h"
#include "hexdom/io/mesh_io.h"
#include "hexdom/io/msh.h"
#include "hexdom/io/surface_formats.h"
#include "hexdom/io/vtk.h"
#include "hexdom/mesh/mesh.h"
#include "hexdom/segmentation/read_manual_labels.h"

namespace {

#define HEXDOM_STR2(x) #x
#define HEXDOM_STR(x) HEXDOM_STR2(x)
const std::string kReader = HEXDOM_STR(HEXDOM_FUZZ_READER);

std::string extension() {
  if (kReader == "k" || kReader == "vtk" || kReader == "vtu" || kReader == "inp" || kReader == "msh" || kReader == "stl" ||
      kReader == "obj")
    return "." + kReader;
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
