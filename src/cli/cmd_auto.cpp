// hexdom autopolycube: structure and patch surface from a labelled surface, automatically.
#include <chrono>
#include <cstdio>
#include <iostream>

#include "commands.h"
#include "hexdom/autopolycube/autopolycube.h"
#include "hexdom/io/mesh_io.h"

namespace hexdom::cli {

namespace {

void add_autopolycube(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "autopolycube",
      "Polycube structure from a labelled surface, with no manual step: the charts (regions of one label\n"
      "1..6) are flattened onto axis-aligned planes on a grid of spacing h = size * 2^level, every grid cell\n"
      "inside becomes a hex block, and the surface is re-split along the grid lines into one patch per\n"
      "boundary square. `hexdom generate -i PATCHES -p STRUCTURE -s LEVEL` takes the two files unchanged.");
  struct Args {
    std::string in, out, patches, polycube;
    autopolycube::AutoPolycubeOptions opt;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("-i,--input", a->in, "labelled surface: label 1..6 (+X, -X, +Y, -Y, +Z, -Z) per triangle as part id (hexdom segment)")
      ->required();
  cmd->add_option("-o,--output", a->out, "structure to write: hex blocks (.k; .vtk, .vtu also work)")->required();
  cmd->add_option("--patches-out", a->patches, "patch surface to write (.k, .obj, .vtk): one patch per boundary square")->required();
  cmd->add_option("--polycube-out", a->polycube, "also write the polycube surface (triangles at their polycube positions, label as part id)");
  cmd->add_option("--size", a->opt.size, "target element size H; 0: the bounding-box diagonal / 30")
      ->capture_default_str()->check(CLI::NonNegativeNumber);
  cmd->add_option("-s,--level", a->opt.level, "subdivision level the structure is meant for: blocks are cells of h = size * 2^level")
      ->capture_default_str()->check(CLI::Range(0, 6));
  cmd->add_option("--max-relabels", a->opt.max_relabels, "charts the label repair may relabel")->capture_default_str();
  cmd->add_option("--max-attempts", a->opt.max_attempts, "relabel-and-retry rounds when the map folds or the cells do not match")
      ->capture_default_str();
  cmd->add_option("--untangle", a->opt.untangle_rounds, "rounds of local moves of interior block vertices")->capture_default_str();
  cmd->callback([a] {
    io::format_of(a->out);
    io::format_of(a->patches);
    if (!a->polycube.empty()) io::format_of(a->polycube);
    a->opt.log = print_log;
    const auto t0 = std::chrono::steady_clock::now();
    const mesh::SurfaceMesh labels = io::read_surface(a->in);
    autopolycube::AutoPolycube progress;
    try {
      autopolycube::autopolycube(labels, a->opt, &progress);
    } catch (const Error&) {
      if (!a->polycube.empty() && progress.polycube.F.rows() > 0) {
        io::write_mesh(a->polycube, mesh::from_surface(progress.polycube));
        std::cerr << "hexdom: wrote the last polycube to " << a->polycube << " for inspection\n";
      }
      throw;
    }
    const auto t1 = std::chrono::steady_clock::now();
    const auto& r = progress;
    io::write_mesh(a->out, r.structure);
    io::write_mesh(a->patches, mesh::from_surface(r.patches));
    if (!a->polycube.empty()) io::write_mesh(a->polycube, mesh::from_surface(r.polycube));
    std::cerr << "hexdom: automatic polycube in " << std::chrono::duration<double>(t1 - t0).count() << " s; wrote " << a->out
              << " and " << a->patches << "\n";
    char line[256];
    std::cout << "charts:             " << r.charts << " (" << r.relabelled << " relabelled, " << r.chords << " chords split)\n";
    std::cout << "planes:             " << r.planes << " (" << r.pushed << " moved by more than a cell)\n";
    std::snprintf(line, sizeof line, "cell size h:        %.6g\n", r.cell);
    std::cout << line;
    std::cout << "blocks:             " << r.blocks << " hex\n";
    std::cout << "boundary squares:   " << r.squares << " (patches)\n";
    std::cout << "block vertices:     " << r.boundary_vertices << " on the surface, " << r.interior_vertices << " inside\n";
    std::snprintf(line, sizeof line, "worst block SJ:     %.4f (%d inverted)\n", r.min_block_quality, r.inverted_blocks);
    std::cout << line;
  });
}

}  // namespace

void add_auto_commands(CLI::App& app) {
  add_autopolycube(app);
}

}  // namespace hexdom::cli
