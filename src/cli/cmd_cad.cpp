// hexdom tessellate: one solid of a STEP, IGES or BREP file to a closed triangle surface whose
// part (patch) ids are the CAD face ids (FreeCAD's Face1, Face2, ...).
#include <cstdio>
#include <iostream>

#include "commands.h"
#include "hexdom/cad/read_shape.h"
#include "hexdom/cad/tessellate.h"
#include "hexdom/io/mesh_io.h"

namespace hexdom::cli {

void add_cad_commands(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "tessellate",
      "Triangulate one solid of a CAD file (.step/.stp, .iges/.igs, .brep/.brp) into a closed surface for "
      "hexdom's stages: near-isotropic triangles of about --size, vertices on the B-rep, each triangle "
      "carrying its CAD face id (FreeCAD's FaceN) as part/patch id");
  struct Args {
    std::string input, out;
    cad::TessellateOptions opt;
    int solid = 0;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("input", a->input, "CAD file: .step, .stp, .iges, .igs, .brep or .brp")->required();
  cmd->add_option("-o,--output", a->out, "triangle surface to write (.k, .stl, .obj, .vtk); .k writes one part per CAD face")
      ->required();
  cmd->add_option("--size", a->opt.size, "target edge length; 0: the bounding-box diagonal / 30")
      ->capture_default_str()->check(CLI::NonNegativeNumber);
  cmd->add_option("--deflection", a->opt.deflection,
                  "largest distance between the triangles and the surface on curved faces; 0: size / 50")
      ->capture_default_str()->check(CLI::NonNegativeNumber);
  cmd->add_option("--angle", a->opt.angle, "largest angle (degrees) an edge may turn on a curved face or edge")
      ->capture_default_str()->check(CLI::NonNegativeNumber);
  cmd->add_option("--min-size", a->opt.min_size, "smallest target edge length from curvature; 0: size / 20")
      ->capture_default_str()->check(CLI::NonNegativeNumber);
  cmd->add_option("--iterations", a->opt.iterations, "remeshing sweeps")->capture_default_str()->check(CLI::Range(0, 100));
  cmd->add_option("--solid", a->solid, "which solid of a multi-solid file (1-based); default: the first, with a warning")
      ->check(CLI::PositiveNumber);
  cmd->callback([a] {
    io::output_format_of(a->out);  // an unknown output type fails before any work
    cad::ReadOptions ro;
    ro.solid = a->solid;
    ro.log = print_log;
    cad::Shape shape = cad::read_shape(a->input, ro);
    a->opt.log = [](int level, const std::string& m) {
      if (level > 0) print_log(level, m);  // warnings only: the sweeps' progress is noise here
    };
    cad::TessellateStats st;
    mesh::SurfaceMesh s = cad::tessellate(shape, a->opt, &st);
    io::write_mesh(a->out, mesh::from_surface(s));
    std::cerr << "hexdom: tessellated " << a->input << " in " << st.seconds << " s; wrote " << a->out << "\n";
    const double err = st.brep_volume != 0 ? 100.0 * (st.volume - st.brep_volume) / st.brep_volume : 0.0;
    char line[256];
    std::cout << "CAD faces:             " << st.faces << "\n";
    std::cout << "triangles:             " << st.triangles << "\n";
    std::cout << "vertices:              " << st.vertices << "\n";
    std::snprintf(line, sizeof line, "target size:           %.6g\n", st.size);
    std::cout << line;
    std::snprintf(line, sizeof line, "edge length:           min %.6g  mean %.6g  max %.6g\n", st.min_edge, st.mean_edge, st.max_edge);
    std::cout << line;
    std::snprintf(line, sizeof line, "min angle:             %.2f deg (planar faces: %.2f deg)\n", st.min_angle,
                  st.min_angle_planar);
    std::cout << line;
    std::cout << "closed 2-manifold:     " << (st.closed ? "yes" : "no") << "\n";
    std::snprintf(line, sizeof line, "volume:                %.9g (B-rep %.9g, %+.4f%%)\n", st.volume, st.brep_volume, err);
    std::cout << line;
  });
}

}  // namespace hexdom::cli
