// hexdom segment, hexdom check, hexdom polycube: the segmentation stage and the polycube boundary.
#include <chrono>
#include <iostream>

#include "commands.h"
#include "hexdom/io/mesh_io.h"
#include "hexdom/io/text.h"
#include "hexdom/segmentation/check_patches.h"
#include "hexdom/segmentation/polycube_boundary.h"
#include "hexdom/segmentation/read_manual_labels.h"
#include "hexdom/segmentation/segment_cvt.h"
#include "hexdom/segmentation/segmentation_stats.h"

namespace hexdom::cli {

namespace {

void add_segment(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "segment",
      "Polycube segmentation: CVT of the triangle normals with generators +-X, +-Y, +-Z (classical energy,\n"
      "then the edge-weighted energy that removes zig-zag boundaries). Writes label 1..6 (+X, -X, +Y, -Y,\n"
      "+Z, -Z) of each triangle as its part id.");
  struct Args {
    std::string in, out, manual;
    bool faces = false, no_faces = false;
    segmentation::CvtOptions opt;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("-i,--input", a->in, "closed triangle surface (.k, .stl, .obj, .vtk); part ids = CAD faces")->required();
  cmd->add_option("-o,--output", a->out, "labelled surface (.k: part id = label; .vtk, .obj, .stl)")->required();
  cmd->add_option("--lambda,--edge-weight", a->opt.edge_weight,
                  "weight of the edge term: d^2 = |n-g|^2/4 + 2 lambda (N - N_same)/N; 0: classical CVT only")
      ->capture_default_str();
  cmd->add_option("--manual", a->manual, "override file: 'triangle label' lines, both 0-based (label 0..5 = +X..-Z)");
  cmd->add_flag("--respect-faces", a->faces,
                "planar CAD faces keep one label, boundaries follow CAD edges where they can (default when the "
                "input has more than one part id)");
  cmd->add_flag("--no-respect-faces", a->no_faces, "ignore the input's part ids");
  cmd->add_option("--classical-sweeps", a->opt.classical_sweeps, "at most this many sweeps of the classical pass")->capture_default_str();
  cmd->add_option("--edge-sweeps", a->opt.edge_sweeps, "at most this many sweeps of the edge-weighted pass")->capture_default_str();
  cmd->add_option("--max-drift", a->opt.max_drift, "degrees a generator may move away from its axis")->capture_default_str();
  cmd->add_option("--ring", a->opt.ring, "neighbourhood of the edge term: triangles within this many edge steps")->capture_default_str();
  cmd->add_option("--planar-angle", a->opt.planar_angle, "degrees: a CAD face whose normals stay this close is planar")->capture_default_str();
  cmd->add_option("--face-majority", a->opt.face_majority, "area share above which a curved CAD face takes one label")->capture_default_str();
  cmd->callback([=] {
    if (a->faces && a->no_faces) throw CLI::ValidationError("--respect-faces and --no-respect-faces exclude each other");
    io::output_format_of(a->out);
    a->opt.respect_faces = a->faces ? segmentation::FaceMode::On : a->no_faces ? segmentation::FaceMode::Off : segmentation::FaceMode::Auto;
    if (!a->manual.empty()) a->opt.manual = segmentation::read_manual_labels(a->manual);
    a->opt.log = print_log;
    auto t0 = std::chrono::steady_clock::now();
    mesh::SurfaceMesh surface = io::read_surface(a->in);
    segmentation::Segmentation seg = segmentation::segment_cvt(surface, a->opt);
    auto t1 = std::chrono::steady_clock::now();
    auto before = segmentation::segmentation_stats(surface, seg.classical);
    auto after = segmentation::segmentation_stats(surface, seg.label);
    surface.patch = seg.label;
    io::write_mesh(a->out, mesh::from_surface(surface));
    std::cerr << "hexdom: segmented " << surface.F.rows() << " triangles in "
              << std::chrono::duration<double>(t1 - t0).count() << " s; wrote " << a->out << "\n";
    std::cout << "classical CVT: " << before.patches << " patches, boundary length " << before.boundary_length
              << ", zig-zag triangles " << before.teeth << "\n"
              << segmentation::to_text(after);
  });
}

void add_check(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "check",
      "Checks the polycube conditions on a segmented surface (patch = connected region of one part id):\n"
      "1) patches of opposite orientations do not share a boundary; 2) every corner is shared by 3 or more\n"
      "patches; 3) a quadrilateral patch has 4 boundary curves, a triangular one 3; every patch is a disk.\n"
      "Exit 0 when valid, 1 with the list of violations otherwise.");
  struct Args {
    std::string in;
    bool json = false, list = false;
    segmentation::CheckOptions opt;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("-i,--input", a->in, "segmented surface: part id per triangle (.k, .obj, .vtk)")->required();
  cmd->add_flag("--json", a->json, "print the report as JSON (patches, corners, violations)");
  cmd->add_flag("--list", a->list, "also list every patch with its orientation, type and curves");
  cmd->add_option("--triangular", a->opt.triangular_ids,
                  "part ids of patches meant to be triangular (default: a patch with 3 curves is triangular)")
      ->delimiter(',');
  cmd->add_option("--opposite-angle", a->opt.opposite_angle,
                  "degrees: touching patches with opposite nearest axes whose normals differ by more are opposite")
      ->capture_default_str();
  cmd->add_option("--corner-defect", a->opt.corner_defect,
                  "degrees: a vertex with a larger angle defect is a corner of the shape and needs 3 patches")
      ->capture_default_str();
  cmd->add_option("--corner-angle", a->opt.corner_angle,
                  "degrees: a curve between two patches turning by more has a corner only 2 patches share (0: off)")
      ->capture_default_str();
  cmd->callback([=] {
    mesh::SurfaceMesh surface = io::read_surface(a->in);
    segmentation::PatchCheck c = segmentation::check_patches(surface, a->opt);
    if (a->json)
      std::cout << segmentation::to_json(c) << std::endl;
    else
      std::cout << segmentation::to_text(c, a->list) << std::flush;
    if (!c.is_valid())
      throw GeometryError(a->in + ": " + std::to_string(c.violations.size()) + " violation" +
                          (c.violations.size() == 1 ? "" : "s") + " of the polycube conditions");
  });
}

void add_polycube(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "polycube",
      "Polycube boundary of a segmented surface, as the original's initial polycube files: the corners\n"
      "(vertices where 3 or more patches meet) as nodes and one shell per patch over its 3 or 4 corners\n"
      "(part id = patch number, in the order of each patch's first triangle).\n"
      "With --auto: the polycube STRUCTURE built automatically (hexdom autopolycube): hex and prism blocks to -o,\n"
      "the surface re-split into one patch per block face to --patches-out (default <output stem>_patches.k);\n"
      "`hexdom generate -i PATCHES -p STRUCTURE -s LEVEL` takes both unchanged.");
  struct Args {
    std::string in, out;
    bool corners = false, automatic = false;
    AutoPolycubeArgs auto_args;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("-i,--input", a->in, "segmented surface: part id per triangle (.k, .obj, .vtk); with --auto labels 1..6 "
                  "(hexdom segment) or patches (each labelled by its nearest axis)")->required();
  cmd->add_option("-o,--output", a->out, "initial polycube, or with --auto the structure (.k; .vtk, .vtu, .obj also work)")->required();
  cmd->add_flag("--corners", a->corners,
                "also write <output stem>_corners.txt ('vertexIndex x y z', 0-based) and <output stem>_edges.vtk "
                "(corners and the boundary curves between them, for display)");
  auto* automatic = cmd->add_flag("--auto", a->automatic, "build the block structure automatically (see hexdom autopolycube)");
  cmd->add_option("--patches-out", a->auto_args.patches, "--auto: patch surface to write; default <output stem>_patches.k");
  add_autopolycube_options(*cmd, a->auto_args);
  for (const char* name : {"--patches-out", "--polycube-out", "--size", "--level", "--max-relabels", "--max-attempts", "--untangle"})
    cmd->get_option(name)->needs(automatic);
  automatic->excludes("--corners");
  cmd->callback([=] {
    if (a->automatic) {
      AutoPolycubeArgs& x = a->auto_args;
      x.in = a->in;
      x.out = a->out;
      if (x.patches.empty()) x.patches = a->out.substr(0, a->out.size() - io::extension(a->out).size() - 1) + "_patches.k";
      run_autopolycube(x);
      return;
    }
    io::output_format_of(a->out);
    mesh::SurfaceMesh surface = io::read_surface(a->in);
    segmentation::PolycubeBoundary b = segmentation::polycube_boundary(surface);
    segmentation::CheckOptions check_options;
    for (const auto& v : segmentation::check_patches(surface, check_options).violations)
      if (v.kind != segmentation::ViolationKind::NotDisk && v.kind != segmentation::ViolationKind::CurveCount)
        print_log(1, v.message);
    io::write_mesh(a->out, segmentation::polycube_shells(b));
    std::string written = a->out;
    if (a->corners) {
      std::string stem = a->out.substr(0, a->out.size() - io::extension(a->out).size() - 1);
      segmentation::write_corner_file(stem + "_corners.txt", b);
      segmentation::write_edges_vtk(stem + "_edges.vtk", surface, b);
      written += ", " + stem + "_corners.txt, " + stem + "_edges.vtk";
    }
    int tris = 0;
    for (const auto& f : b.faces) tris += f.corners.size() == 3;
    std::cout << b.corner_vertices.size() << " corners, " << b.edges.size() << " edges, " << b.faces.size()
              << " patches (" << b.faces.size() - tris << " quadrilateral, " << tris << " triangular)\n";
    std::cerr << "hexdom: wrote " << written << "\n";
  });
}

}  // namespace

void add_segmentation_commands(CLI::App& app) {
  add_segment(app);
  add_check(app);
  add_polycube(app);
}

}  // namespace hexdom::cli
