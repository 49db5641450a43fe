// hexdom autopolycube: structure and patch surface from a labelled surface, automatically.
// hexdom mesh: a surface or a CAD part to a hex mesh with no manual step.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>

#include "commands.h"
#include "hexdom/autopolycube/autopolycube.h"
#include "hexdom/pipeline/mesh_surface.h"
#include "hexdom/pipeline/mesh_cad.h"
#include "hexdom/cad/read_shape.h"
#include "hexdom/cad/snap.h"
#include "hexdom/cad/tessellate.h"
#include "hexdom/common/format.h"
#include "hexdom/io/mesh_io.h"
#include "hexdom/io/text.h"
#include "hexdom/segmentation/labels_of_parts.h"

namespace hexdom::cli {

void add_autopolycube_options(CLI::App& cmd, AutoPolycubeArgs& a) {
  cmd.add_option("--polycube-out", a.polycube, "also write the polycube surface (triangles at their polycube positions, label as part id)");
  cmd.add_option("--size", a.opt.size, "target element size H; 0: the bounding-box diagonal / 30")
      ->capture_default_str()->check(CLI::NonNegativeNumber);
  cmd.add_option("-s,--level", a.opt.level, "subdivision level the structure is meant for: blocks are cells of h = size * 2^level")
      ->capture_default_str()->check(CLI::Range(0, 6));
  cmd.add_option("--max-relabels", a.opt.max_relabels, "charts the label repair may relabel")->capture_default_str();
  cmd.add_option("--max-attempts", a.opt.max_attempts, "relabel-and-retry rounds when the map folds or the cells do not match")
      ->capture_default_str();
  cmd.add_option("--max-same-problem", a.opt.max_same_problem,
                 "rounds in a row that may end in the very same problem (the same charts failing the same way) before "
                 "giving up: the label repair is then not converging")
      ->capture_default_str()->check(CLI::PositiveNumber);
  cmd.add_option("--untangle", a.opt.untangle_rounds, "rounds of local moves of interior block vertices")->capture_default_str();
  cmd.add_option("--sliver-ratio", a.opt.sliver_ratio,
                 "strip charts (1 or 2 squares wide) whose width across is at most this share of their length along "
                 "become prism blocks (the knife edge of a wedge-like feature); 0: hex blocks only")
      ->capture_default_str()->check(CLI::Range(0.0, 1.0));
}

void run_autopolycube(AutoPolycubeArgs& a) {
  io::output_format_of(a.out);
  io::output_format_of(a.patches);
  if (!a.polycube.empty()) io::output_format_of(a.polycube);
  a.opt.log = print_log;
  const auto t0 = std::chrono::steady_clock::now();
  mesh::SurfaceMesh labels = io::read_surface(a.in);
  bool from_normals = false;
  try {
    labels.patch = segmentation::labels_of_parts(labels, &from_normals);
  } catch (const InputError& e) {
    throw InputError(a.in + ": " + e.what());
  }
  if (from_normals)
    print_log(0, a.in + ": part ids are patches, not labels 1..6: each patch labelled by the axis nearest its normal");
  autopolycube::AutoPolycube progress;
  try {
    autopolycube::autopolycube(labels, a.opt, &progress);
  } catch (const Error&) {
    if (!a.polycube.empty() && progress.polycube.F.rows() > 0) {
      io::write_mesh(a.polycube, mesh::from_surface(progress.polycube));
      std::cerr << "hexdom: wrote the last polycube to " << a.polycube << " for inspection\n";
    }
    throw;
  }
  const auto t1 = std::chrono::steady_clock::now();
  const auto& r = progress;
  io::write_mesh(a.out, r.structure);
  io::write_mesh(a.patches, mesh::from_surface(r.patches));
  if (!a.polycube.empty()) io::write_mesh(a.polycube, mesh::from_surface(r.polycube));
  std::cerr << "hexdom: automatic polycube in " << std::chrono::duration<double>(t1 - t0).count() << " s; wrote " << a.out
            << " and " << a.patches << "\n";
  char line[256];
  std::cout << "charts:             " << r.charts << " (" << r.relabelled << " relabelled, " << r.chords << " chords split)\n";
  std::cout << "planes:             " << r.planes << " (" << r.pushed << " moved by more than a cell)\n";
  std::snprintf(line, sizeof line, "cell size h:        %.6g\n", r.cell);
  std::cout << line;
  std::cout << "blocks:             " << r.blocks - r.prism_blocks - r.tet_blocks << " hex, " << r.prism_blocks << " prism, "
            << r.tet_blocks << " tet\n";
  if (r.slivers == 0)
    std::cout << "boundary squares:   " << r.squares << " (patches)\n";
  else
    std::cout << "boundary squares:   " << r.squares << " (" << r.patches.patch.maxCoeff() << " patches: the squares of " << r.slivers
              << " sliver strips joined their neighbours)\n";
  std::cout << "block vertices:     " << r.boundary_vertices << " on the surface, " << r.interior_vertices << " inside\n";
  std::snprintf(line, sizeof line, "worst block SJ:     %.4f (%d inverted)\n", r.min_block_quality, r.inverted_blocks);
  std::cout << line;
}

namespace {

void add_autopolycube(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "autopolycube",
      "Polycube structure from a labelled surface, with no manual step: the charts (regions of one label\n"
      "1..6) are flattened onto axis-aligned planes on a grid of spacing h = size * 2^level, every grid cell\n"
      "inside becomes a hex block, and the surface is re-split along the grid lines into one patch per\n"
      "boundary square. Where a thin strip chart runs along a wedge-like feature (a knife edge), its blocks\n"
      "become prisms (--sliver-ratio) and its squares join the neighbouring patches.\n"
      "`hexdom generate -i PATCHES -p STRUCTURE -s LEVEL` takes the two files unchanged.\n"
      "Also `hexdom polycube --auto`.");
  auto a = std::make_shared<AutoPolycubeArgs>();
  cmd->add_option("-i,--input", a->in, "labelled surface: label 1..6 (+X, -X, +Y, -Y, +Z, -Z) per triangle as part id (hexdom segment); "
                  "a surface whose part ids are patches gets each patch's nearest axis")
      ->required();
  cmd->add_option("-o,--output", a->out, "structure to write: hex and prism blocks (.k; .vtk, .vtu also work)")->required();
  cmd->add_option("--patches-out", a->patches, "patch surface to write (.k, .obj, .vtk): one patch per boundary face of the structure")->required();
  add_autopolycube_options(*cmd, *a);
  cmd->callback([a] { run_autopolycube(*a); });
}

bool is_cad_file(const std::string& path) {
  const auto dot = path.find_last_of('.');
  if (dot == std::string::npos) return false;
  std::string ext = path.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == "step" || ext == "stp" || ext == "iges" || ext == "igs" || ext == "brep" || ext == "brp";
}

// "part.vtk" -> "part": where the intermediate files go.
std::string stem_of(const std::string& path) {
  const auto dot = path.find_last_of('.'), slash = path.find_last_of('/');
  return dot == std::string::npos || (slash != std::string::npos && dot < slash) ? path : path.substr(0, dot);
}

// The snap's line of `hexdom mesh`'s log.
void print_snap(const cad::SnapReport& q, double seconds) {
  char line[400];
  std::snprintf(line, sizeof line,
                "snap: %d boundary nodes onto %d faces, %d edges, %d vertices; B-rep distance max %.3g -> %.3g "
                "(%.2e of the diagonal); worst SJ %.3f -> %.3f, %d inverted, in %.2f s",
                q.boundary_nodes, q.face_nodes, q.edge_nodes, q.vertex_nodes, q.max_before, q.max_after,
                q.diagonal > 0 ? q.max_after / q.diagonal : 0.0, q.worst_sj_before, q.worst_sj, q.inverted, seconds);
  print_log(0, line);
}

// The boundary faces that cross a CAD edge (io::FaceSets::across), with their share of the boundary's
// area: FreeCAD's face loads leave them out.
void print_crossing(const mesh::Mesh& m, const io::FaceSets& sets) {
  double all = 0, across = 0;
  int count = 0;
  for (size_t i = 0; i < sets.faces.size() && i < sets.across.size(); ++i) {
    const double a = mesh::face_area_vector(m, sets.faces[i]).norm();
    all += a;
    if (sets.across[i]) across += a, ++count;
  }
  if (count == 0) return;
  print_log(0, fmt("faces: %.0f of %.0f boundary faces (%.2f%% of the area) cross a CAD edge; a face load in FreeCAD "
                   "leaves them out",
                   double(count), double(sets.faces.size()), all > 0 ? 100 * across / all : 0.0));
}

const char* const kMeshHelp =
      "Hex mesh of a closed surface or a CAD part with no manual step, by one of two paths (--method): the\n"
      "polycube (segment -> autopolycube -> generate -> improve; aligned with the part, the coarsest mesh) or\n"
      "the overlay grid (cells of the element size laid over the part, the ones well inside kept, one layer\n"
      "of cells out to the surface with its curves and corners, then optimised; meshes any closed solid).\n"
      "auto (the default) runs the cheapest meshes first: the polycube's first candidate (one segmentation,\n"
      "kept alone when its mesh meets every target: no inverted cell, a worst scaled Jacobian >= 0.3, a volume\n"
      "within 1%, a largest edge ratio <= 10); otherwise the overlay grid too (it runs beside the polycube on\n"
      "a second thread and is called off when the polycube's first mesh is kept); and only when neither meets the\n"
      "first three targets, the polycube's further candidates (or, when its labelling defeated the repair,\n"
      "the segmentation's further edge weights), the better kept.\n"
      "Under auto the polycube path has a time budget (--polycube-seconds, 20 s; for CAD parts over all its\n"
      "polycube attempts, from the end of the first tessellation): once it has passed the path stops (the\n"
      "improvement ends its round, no further candidate or tessellation is tried) and, without a mesh that\n"
      "meets the targets, the overlay grid runs.\n"
      "One progress line per stage, then the quality summary. The structure has hex blocks, and\n"
      "prism blocks along wedge-like features (knife edges; --sliver-ratio). CAD files (.step/.stp, .iges/.igs,\n"
      ".brep/.brp) are tessellated first (hexdom tessellate, CAD faces kept for the segmentation), and the\n"
      "final boundary nodes are put exactly on the B-rep (stage snap: faces, edges, vertices; interior\n"
      "untangled and optimised with the boundary held).\n"
      "Candidates, chosen by measured criteria: the polycube first keeps the widths of holes (walls facing\n"
      "each other across a void are as many cells apart as in the input); when that mesh has an inverted\n"
      "cell, a worst scaled Jacobian below 0.3 or a volume more than 1% off the input surface's, the\n"
      "polycube with the least-squares plane offsets is meshed too, and the better kept: fewer inverted\n"
      "cells, then a worst SJ >= 0.3, then a volume within 1%, then the higher worst SJ. When inverted\n"
      "cells remain at level s > 0 or the worst SJ is below 0.3, the same again at level s - 1 (a grid of\n"
      "half the spacing), the better kept by the same order.\n"
      "A part lying at an angle (its faces fit axes turned from the model's by more than the model's own\n"
      "fit them) is segmented and given its polycube in that turned frame; the mesh is in the model's\n"
      "coordinates (--no-align: the model's axes).";

// "10=1.5" or "Face10=1.5" (`prefix` "Face"; "Edge" for edges): a number and a size; InputError
// naming the option and the text otherwise.
std::pair<int, double> parse_local_size(const std::string& text, const std::string& option, const std::string& prefix) {
  const size_t eq = text.find('=');
  std::string item = text.substr(0, eq == std::string::npos ? 0 : eq);
  if (item.rfind(prefix, 0) == 0) item = item.substr(prefix.size());
  std::pair<int, double> l{0, 0.0};
  try {
    size_t used = 0, used2 = 0;
    l.first = std::stoi(item, &used);
    l.second = std::stod(text.substr(eq + 1), &used2);
    if (used != item.size() || used2 != text.size() - eq - 1) throw std::invalid_argument(text);
  } catch (const std::logic_error&) {
    throw InputError(option + " " + text + ": expected " + (prefix == "Face" ? "FACE" : "EDGE") + "=SIZE, a number (or " +
                     prefix + "<number>) and a size, as 10=1.5");
  }
  if (l.first < 1 || !(l.second > 0))
    throw InputError(option + " " + text + ": the " + (prefix == "Face" ? "face" : "edge") +
                     " number must be at least 1 and the size positive");
  return l;
}

// `hexdom mesh`'s options of the element size: --size, its bounds, cells across, local sizes on faces
// (into opt) and edges (into edge_sizes), growth rate, level, octree.
void add_size_options(CLI::App& cmd, pipeline::MeshSurfaceOptions& opt, std::vector<std::pair<int, double>>& edge_sizes) {
  cmd.add_option("--size", opt.size, "target element size H; 0: the bounding-box diagonal / 30")
      ->capture_default_str()->check(CLI::NonNegativeNumber);
  cmd.add_option("--max-size", opt.max_size, "largest element size: the size (given or default) is at most this; 0: no bound")
      ->capture_default_str()->check(CLI::NonNegativeNumber);
  cmd.add_option("--min-size", opt.min_size,
                 "smallest element size: the size is at least this, and cells made thinner for a thin part are not "
                 "shorter (it then gets fewer cells across); 0: no bound")
      ->capture_default_str()->check(CLI::NonNegativeNumber);
  cmd.add_option("--cells-across", opt.across_thin,
                 "cells across a part thin along an axis (a plate, a rod), none longer than 5 times the shortest side; "
                 "0: cubic cells of the size")
      ->capture_default_str()->check(CLI::NonNegativeNumber);
  cmd.add_option_function<std::vector<std::string>>(
         "--face-size",
         [&opt](const std::vector<std::string>& items) {
           for (const std::string& item : items) {
             const auto [face, size] = parse_local_size(item, "--face-size", "Face");
             opt.overlay.local_sizes.push_back({face, size, {}});
           }
         },
         "cell size on one face, as FACE=SIZE (FACE: the face's number, FreeCAD's Face<number>, or Face<number>); "
         "repeat for more faces. Both paths refine by thirds near those faces, graded back to the size (the overlay "
         "its grid, the polycube its mesh): the smallest size within 20%, others within a factor 1.7; auto keeps the "
         "mesh within 20% of more sizes (median cell on each face), after the quality targets")
      ->allow_extra_args(false);
  cmd.add_option_function<std::vector<std::string>>(
         "--edge-size",
         [&edge_sizes](const std::vector<std::string>& items) {
           for (const std::string& item : items) edge_sizes.push_back(parse_local_size(item, "--edge-size", "Edge"));
         },
         "CAD files: cell size along one edge, as EDGE=SIZE (EDGE: FreeCAD's Edge<number>, or Edge<number>); repeat "
         "for more edges. As --face-size: both paths refine near the edge")
      ->allow_extra_args(false);
  cmd.add_option("--growth-rate", opt.overlay.growth_rate,
                 "with --face-size / --edge-size: how fast cells grow from their size back to the element size, per cell "
                 "(in (1, 3]; the refined band around the face is wider the smaller it is)")
      ->capture_default_str();
  cmd.add_option("-s,--level", opt.level, "subdivision level: blocks are grid cells of h = size * 2^level")
      ->capture_default_str()->check(CLI::Range(0, 6));
  cmd.add_option("--octree-levels", opt.overlay.octree_levels, "overlay grid: cells split in 27, up to this many "
                 "times, where a wall is thinner than a cell (experimental: many cells on thin shells); 0: off")->check(CLI::Range(0, 3));
  cmd.add_flag("--pillow-curves", opt.overlay.pillow_curves,
               "overlay grid: a sheet of wedges along each curve (CAD edge), so that every boundary face lies on one CAD "
               "face and a face load in FreeCAD takes them all; more cells, and on some parts a lower worst SJ");
}

// For an .inp, .msh or .k output (a .vtu one with `vtu_faces`), the boundary faces of `m` tagged with
// the patch (CAD face) of `surface` each lies on, and the nodes of each (the snap's `node_faces`
// when snapped: io::face_sets), for the Face<k> sets; none for other formats or without a surface.
io::WriteOptions face_sets_for(const std::string& out, const mesh::Mesh& m, const mesh::SurfaceMesh& surface,
                               bool vtu_faces = false, const std::vector<std::vector<int>>& node_faces = {}) {
  io::WriteOptions w;
  const io::Format f = io::format_of(out);
  if (f == io::Format::Inp || f == io::Format::Msh || f == io::Format::K || (vtu_faces && f == io::Format::Vtu))
    w.face_sets = io::face_sets(m, surface, node_faces);
  return w;
}

// `hexdom mesh`'s arguments and options.
struct MeshArgs {
  std::string in, out, report;
  bool keep = false, allow_inverted = false, no_improve = false, no_snap = false, no_align = false;
  bool boundary_faces = false;
  int solid = 0;
  std::string method = "auto";
  std::vector<std::pair<int, double>> edge_sizes;
  pipeline::MeshSurfaceOptions opt;
};

void add_mesh_options(CLI::App* cmd, const std::shared_ptr<MeshArgs>& a) {
  cmd->add_option("input", a->in, "closed triangle surface (.k, .stl, .obj, .vtk) or CAD part (.step, .stp, .iges, .igs, .brep, .brp)")
      ->required();
  cmd->add_option("-o,--output", a->out, "mesh to write (.vtk, .vtu, .inp, .k)")->required();
  cmd->add_option("--order", a->opt.order,
                  "element order: 1 (hex8, wedge6, tet4) or 2 (hex20, wedge15, tet10: a node on every cell edge, those of "
                  "the boundary on the B-rep or the input surface; .vtk, .vtu, .inp)")
      ->capture_default_str()->check(CLI::Range(1, 2));
  cmd->add_option("--method", a->method,
                  "meshing path: polycube (aligned, coarsest), overlay (a grid laid over the part: meshes any closed "
                  "solid), or auto: the polycube, and the overlay grid too when the polycube fails or misses a target, "
                  "the better kept")
      ->capture_default_str()->check(CLI::IsMember({"auto", "polycube", "overlay"}));
  cmd->add_option("--threads", a->opt.threads, "threads (0: one per core); same mesh whatever the number")->check(CLI::NonNegativeNumber);
  cmd->add_option("--polycube-seconds", a->opt.polycube_seconds,
                  "time budget of the polycube path in seconds (0: no limit). auto: once it has passed the polycube "
                  "path stops with the mesh it has, or fails, and the overlay grid runs (CAD parts: counted from the end of "
                  "the first tessellation). polycube: no limit unless given, then counted from the start; when it passes "
                  "before there is a mesh, an error (exit 5) and no output file")
      ->capture_default_str()->check(CLI::NonNegativeNumber);
  cmd->add_option("--time-limit", a->opt.time_limit,
                  "seconds the whole run may take (0: no limit); past it the run stops within a fraction of a second "
                  "with an error naming the step it was in (exit 5) and writes nothing")
      ->capture_default_str()->check(CLI::NonNegativeNumber);
  add_size_options(*cmd, a->opt, a->edge_sizes);
  cmd->add_option("--lambda,--edge-weight", a->opt.segment.edge_weight, "segmentation: weight of the edge term")->capture_default_str();
  cmd->add_option("--max-relabels", a->opt.polycube.max_relabels, "charts the label repair may relabel")->capture_default_str();
  cmd->add_option("--sliver-ratio", a->opt.polycube.sliver_ratio,
                  "strip charts whose width across is at most this share of their length along become prism blocks; "
                  "0: hex blocks only")
      ->capture_default_str()->check(CLI::Range(0.0, 1.0));
  cmd->add_flag("--no-improve", a->no_improve, "skip the improvement stage");
  cmd->add_flag("--no-align", a->no_align,
                "segment and build the polycube in the model's axes, not in the frame the faces fit best (a part "
                "lying at an angle is turned into that frame and back; the default size is that frame's box diagonal / 30)");
  cmd->add_flag("--no-snap", a->no_snap, "CAD files: leave the boundary nodes on the tessellation instead of the B-rep");
  cmd->add_option("--solid", a->solid, "CAD files: mesh only this solid (1-based); default: every solid, solid k in region k")->check(CLI::PositiveNumber);
  cmd->add_flag("--boundary-faces", a->boundary_faces,
                ".vtu output: also the boundary faces, as quads / triangles after the volume cells, with a cell array "
                "face_id naming each one's CAD face (FreeCAD's Face<k>; 0 for the volume cells)");
  cmd->add_flag("--keep", a->keep,
                "also write <output stem>_surface.k (the triangle surface meshed: the tessellation kept, or the "
                "input), and from the polycube path _labels.k, _structure.k, _patches.k and _polycube.vtk (on failure "
                "the labels and the polycube are always written)");
  cmd->add_option("--report", a->report, "also write the final quality report as JSON to this file");
  cmd->add_flag("--allow-inverted", a->allow_inverted, "exit 0 even if inverted cells remain (they are still reported)");
  cmd->add_flag("-v,--verbose", a->opt.verbose, "also print the stages' own messages");
}

void add_mesh(CLI::App& app) {
  auto* cmd = app.add_subcommand("mesh", kMeshHelp);
  auto a = std::make_shared<MeshArgs>();
  add_mesh_options(cmd, a);
  cmd->callback([a, cmd] {
    io::output_format_of(a->out);
    a->opt.log = print_log;
    a->opt.improve = !a->no_improve;
    a->opt.align = !a->no_align;
    a->opt.method = pipeline::method_from_name(a->method);
    a->opt.input_name = a->in;  // the input checks' messages name the file
    pipeline::check_size_bounds(a->opt);  // --min-size above --max-size: an error before any work
    // --method polycube honours the budget only when it is given; it starts now, before reading.
    if (a->opt.method == pipeline::Method::Polycube && cmd->count("--polycube-seconds") > 0)
      a->opt.deadline = Deadline::in(a->opt.polycube_seconds);
    const std::string stem = stem_of(a->out);
    mesh::SurfaceMesh surface;
    cad::Shape shape;
    double reference_volume = 0;
    const char* reference = "surface";
    pipeline::MeshSurfaceRun run;
    bool snapped = false;
    std::vector<std::vector<int>> node_faces;  // the CAD faces each boundary node was snapped onto
    cad::SnapReport snap;
    double snap_seconds = 0;
    auto write_intermediate = [&](bool all) {
      if (run.labels.F.rows() > 0) io::write_mesh(stem + "_labels.k", mesh::from_surface(run.labels));
      if (run.polycube.polycube.F.rows() > 0) io::write_mesh(stem + "_polycube.vtk", mesh::from_surface(run.polycube.polycube));
      if (all && a->keep && surface.F.rows() > 0) io::write_mesh(stem + "_surface.k", mesh::from_surface(surface));
      if (all && run.polycube.structure.num_cells() > 0) {
        io::write_mesh(stem + "_structure.k", run.polycube.structure);
        io::write_mesh(stem + "_patches.k", mesh::from_surface(run.polycube.patches));
      }
    };
    auto failed = [&] {
      write_intermediate(true);
      if (run.labels.F.rows() > 0)  // (none when the input check refused the surface)
        print_log(1, "stage " + run.stage + " failed; wrote " + stem + "_labels.k" +
                         (run.polycube.polycube.F.rows() ? " and " + stem + "_polycube.vtk" : std::string()) + " for inspection");
    };
    if (is_cad_file(a->in)) {
      cad::ReadOptions ro;
      ro.solid = a->solid;
      ro.log = print_log;
      const std::vector<cad::Shape> solids = cad::read_solids(a->in, ro);
      shape = solids.front();
      pipeline::MeshCadOptions co;
      co.tessellation.size = a->opt.size;
      co.tessellation.size_in_frame = !a->no_align;
      co.mesh = a->opt;
      co.log = print_log;
      co.snap = !a->no_snap;
      co.edge_sizes = a->edge_sizes;
      if (a->opt.verbose) co.snap_options.log = print_log;
      pipeline::MeshCadRun cr;
      if (solids.size() > 1) {
        print_log(0, a->in + " holds " + std::to_string(solids.size()) +
                         " solids: each is meshed, its cells in region k for solid k (--solid N meshes one)");
        pipeline::MeshSolidsRun sr;
        try {
          pipeline::mesh_cad_solids(solids, co, &sr);
        } catch (const TimeLimitError&) {
          throw;
        } catch (const Error&) {
          if (!sr.solids.empty()) run = std::move(sr.solids.back().run);
          failed();
          throw;
        }
        cr = std::move(sr.part);
      } else {
        try {
          pipeline::mesh_cad_part(shape, co, &cr);
        } catch (const TimeLimitError&) {
          throw;  // the run was stopped, not a stage: nothing to inspect
        } catch (const Error&) {
          run = std::move(cr.run);
          surface = std::move(cr.surface);
          failed();
          throw;
        }
      }
      surface = std::move(cr.surface);
      run = std::move(cr.run);
      snapped = cr.snapped;
      if (snapped) node_faces = std::move(cr.snap.faces);
      snap = cr.snap.report;
      snap_seconds = cr.snap_seconds;
      reference_volume = cr.stats.brep_volume;
      reference = "B-rep";
      if (cr.tessellation_factor != 1)
        print_log(0, fmt("tessellate: the mesh is the one of the tessellation at %.2f x the size (%.0f triangles)",
                         cr.tessellation_factor, cr.stats.triangles));
    } else {
      if (!a->edge_sizes.empty())
        throw InputError("--edge-size needs a CAD part (.step, .iges, .brep): " + a->in + " is a triangle surface");
      surface = io::read_surface(a->in);
      try {
        pipeline::mesh_surface(surface, a->opt, &run);
      } catch (const TimeLimitError&) {
        throw;
      } catch (const Error&) {
        failed();
        throw;
      }
    }
    if (reference_volume == 0) reference_volume = run.surface_volume;
    print_log(0, "kept: " + pipeline::method_name(run.method) + " path, " + pipeline::choice_text(run));
    if (snapped) print_snap(snap, snap_seconds);
    const io::WriteOptions sets = face_sets_for(a->out, run.mesh, surface, a->boundary_faces, node_faces);
    if (snapped) print_crossing(run.mesh, sets.face_sets.empty() ? io::face_sets(run.mesh, surface, node_faces) : sets.face_sets);
    if (a->keep) write_intermediate(true);
    io::write_mesh(a->out, run.mesh, sets);
    if (!a->report.empty())
      io::write_atomically(a->report, false, [&](std::ostream& o) { o << quality::to_json(run.quality) << "\n"; });
    std::cerr << "hexdom: wrote " << a->out << "\n";
    std::cout << quality::to_text(run.quality);
    char line[200];
    std::snprintf(line, sizeof line, "%s volume %.10g (%+.3f%%)\n", reference, reference_volume,
                  reference_volume != 0 ? 100.0 * (run.quality.total_volume - reference_volume) / reference_volume : 0.0);
    std::cout << line;
    const int inverted = quality::inverted_cells(run.quality);
    if (inverted > 0 && !a->allow_inverted)
      throw MeshingError(std::to_string(inverted) + " inverted cells remain after improvement; " + a->out +
                         " was written so that they can be inspected (--allow-inverted to accept)");
  });
}

}  // namespace

void add_auto_commands(CLI::App& app) {
  add_autopolycube(app);
  add_mesh(app);
}

}  // namespace hexdom::cli
