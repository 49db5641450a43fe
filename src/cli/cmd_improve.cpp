#include <iostream>

#include "commands.h"
#include "hexdom/io/k_file.h"
#include "hexdom/io/mesh_io.h"
#include "hexdom/io/text.h"
#include "hexdom/optimize/improve.h"

namespace hexdom::cli {

void add_improve(CLI::App& app) {
  auto* cmd = app.add_subcommand("improve", "Pillowing, smoothing and Jacobian optimisation of a hex / prism / tet mesh");
  struct Args {
    std::string in, out, surface, sharp, report;
    bool allow_inverted = false;
    optimize::ImproveOptions opt;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("-i,--input", a->in, "volume mesh (.vtk, .k)")->required();
  cmd->add_option("-o,--output", a->out, "improved mesh (.vtk, .vtu, .k, .inp)")->required();
  cmd->add_option("--surface", a->surface, "surface the boundary must stay on (e.g. the patch file); default: the mesh's own boundary");
  cmd->add_flag("--pillow", a->opt.pillow, "insert one layer of cells along the boundary");
  cmd->add_option("--smooth", a->opt.smooth, "smoothing passes");
  cmd->add_option("--threads", a->opt.threads, "threads (0: one per core); the mesh is the same whatever the number")
      ->capture_default_str()->check(CLI::NonNegativeNumber);
  cmd->add_option("--optimize", a->opt.optimize, "Jacobian optimisation rounds");
  auto* sharp = cmd->add_option("--sharp", a->sharp, "sharp-feature node file (last integer per line: 0-based node index)");
  cmd->add_option("--feature-angle", a->opt.feature_angle, "boundary edges whose faces' normals differ by more than this many degrees are sharp")
      ->capture_default_str()->excludes(sharp);
  cmd->add_option("--max-edge-ratio", a->opt.max_edge_ratio,
                  "then move the nodes of cells whose edge ratio is above this to lower it, no cell at or above 0.3 "
                  "taken below it, each type's worst scaled Jacobian kept, then lowered in two steps towards 0.3 while "
                  "cells stay above this (0: off; hexdom mesh uses 10)")
      ->capture_default_str()->check(CLI::NonNegativeNumber);
  cmd->add_option("--report", a->report, "also write the quality report after improvement as JSON to this file");
  cmd->add_flag("--allow-inverted", a->allow_inverted, "exit 0 even if inverted cells remain (they are still reported)");
  cmd->footer("With no stage flags, runs the recommended sequence: pillow, then smoothing and optimisation until the worst cell stops "
              "improving, then passes that raise the mean scaled Jacobian without lowering the worst hex, prism or tet.");
  cmd->callback([=] {
    io::output_format_of(a->out);
    mesh::Mesh m = io::read_mesh(a->in);
    if (!a->surface.empty()) a->opt.surface = io::read_surface(a->surface);
    if (!a->sharp.empty()) a->opt.sharp_nodes = io::read_sharp_nodes(a->sharp);
    a->opt.log = print_log;
    auto r = optimize::improve(m, a->opt);
    io::write_mesh(a->out, r.mesh);
    if (!a->report.empty())
      io::write_atomically(a->report, false, [&](std::ostream& o) { o << quality::to_json(r.after) << "\n"; });
    std::cout << "before:\n" << quality::to_text(r.before) << "after:\n" << quality::to_text(r.after);
    const int inverted = quality::inverted_cells(r.after);
    if (inverted > 0 && !a->allow_inverted)
      throw MeshingError(std::to_string(inverted) + " inverted cells remain after improvement; " + a->out +
                         " was written so that they can be inspected (--allow-inverted to accept)");
  });
}

}  // namespace hexdom::cli
