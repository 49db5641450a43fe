#include <chrono>
#include <iostream>

#include "commands.h"
#include "hexdom/generation/generate.h"
#include "hexdom/io/k_file.h"
#include "hexdom/io/mesh_io.h"
#include "hexdom/io/text.h"
#include "hexdom/quality/report.h"

namespace hexdom::cli {

void add_generate(CLI::App& app) {
  auto* cmd = app.add_subcommand("generate", "Hex-dominant mesh from a segmented surface and a polycube structure");
  struct Args { std::string patches, structure, out, report; bool json = false; generation::GenerateOptions opt; };
  auto a = std::make_shared<Args>();
  cmd->add_option("-i,--input", a->patches, "segmented surface: triangles with a patch id each (.k, .obj, .vtk)")->required();
  cmd->add_option("-p,--structure", a->structure, "polycube structure: hex, prism and tet blocks (.k, .vtk)")->required();
  cmd->add_option("-s,--level", a->opt.level, "subdivision level: 2^s cells per block edge (0..6)")->capture_default_str();
  cmd->add_option("-o,--output", a->out, "output mesh (.vtk, .vtu, .k, .inp)")->required();
  cmd->add_option("--relax", a->opt.relax_sweeps, "sweeps of validity-preserving relaxation inside the volume")->capture_default_str();
  cmd->add_flag("--untangle,!--no-untangle", a->opt.untangle,
                "after the plain relaxation, untangle the cells it leaves inverted (boundary nodes may slide within "
                "the surface); on by default, --no-untangle turns it off");
  cmd->add_option("--threads", a->opt.threads, "threads for the patch maps (0: one per hardware thread; same output)")
      ->capture_default_str();
  cmd->add_option("--report", a->report, "also write the quality report as JSON to this file");
  cmd->callback([=] {
    io::output_format_of(a->out);
    auto t0 = std::chrono::steady_clock::now();
    mesh::SurfaceMesh surface = io::read_surface(a->patches);
    mesh::Mesh structure = io::read_mesh(a->structure);
    a->opt.log = print_log;
    generation::GenerateStats st;
    mesh::Mesh m = generation::generate(surface, structure, a->opt, &st);
    auto t1 = std::chrono::steady_clock::now();
    io::write_mesh(a->out, m);
    auto report = quality::quality_report(m);
    if (!a->report.empty())
      io::write_atomically(a->report, false, [&](std::ostream& o) { o << quality::to_json(report) << "\n"; });
    std::cerr << "hexdom: generated " << m.num_cells() << " cells, " << m.num_nodes() << " nodes in "
              << std::chrono::duration<double>(t1 - t0).count() << " s; wrote " << a->out << "\n";
    std::cout << quality::to_text(report);
  });
}

}  // namespace hexdom::cli
