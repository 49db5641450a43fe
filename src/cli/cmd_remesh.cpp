// hexdom remesh: a closed triangle surface remeshed onto itself (near-equilateral triangles).
#include <iostream>

#include "commands.h"
#include "hexdom/io/mesh_io.h"
#include "hexdom/mesh/remesh_triangles.h"

namespace hexdom::cli {

void add_remesh(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "remesh",
      "Remesh a closed triangle surface onto itself: near-equilateral triangles of about --size, every vertex on\n"
      "the input triangles, part ids (CAD faces) kept with the curves where two parts meet and their corners,\n"
      "and sharp edges kept as curves (--feature-angle). For surfaces from other tools (STL exports with\n"
      "needle triangles) before `hexdom segment` or `hexdom mesh`.");
  struct Args {
    std::string in, out;
    mesh::RemeshTrianglesOptions opt;
    bool verbose = false;
  };
  auto a = std::make_shared<Args>();
  a->opt.feature_angle = 45;
  cmd->add_option("-i,--input", a->in, "closed triangle surface (.k, .stl, .obj, .vtk); part ids = faces")->required();
  cmd->add_option("-o,--output", a->out, "remeshed surface (.k, .stl, .obj, .vtk)")->required();
  cmd->add_option("--size", a->opt.size, "target edge length; 0: the bounding-box diagonal / 30")
      ->capture_default_str()->check(CLI::NonNegativeNumber);
  cmd->add_option("--feature-angle", a->opt.feature_angle,
                  "degrees: edges whose triangles turn by more than this are kept as curves; 0: part ids only")
      ->capture_default_str()->check(CLI::Range(0.0, 180.0));
  cmd->add_option("--iterations", a->opt.iterations, "remeshing sweeps")->capture_default_str()->check(CLI::Range(0, 100));
  cmd->add_flag("-v,--verbose", a->verbose, "print every sweep");
  cmd->callback([a] {
    io::output_format_of(a->out);
    const mesh::SurfaceMesh in = io::read_surface(a->in);
    a->opt.log = [a](int level, const std::string& message) {
      if (a->verbose || level > 0 || message.rfind("remesh sweep", 0) != 0) print_log(level, message);
    };
    mesh::SurfaceMesh out;
    try {
      out = mesh::remesh_triangles(in, a->opt);
    } catch (const InputError& e) {
      throw InputError(a->in + ": " + e.what());
    }
    io::write_mesh(a->out, mesh::from_surface(out));
    std::cerr << "hexdom: wrote " << a->out << " (" << out.F.rows() << " triangles, " << out.V.rows() << " vertices)\n";
  });
}

}  // namespace hexdom::cli
