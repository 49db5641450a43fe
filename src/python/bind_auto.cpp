// _hexdom's automatic path: autopolycube (structure and patch surface from a labelled surface) and
// mesh_surface (segment -> autopolycube -> generate -> improve in one call). Surfaces come in as
// (V #V x 3, F #F x 3, patch #F); meshes go out as (V, cells #C x 8 -1 padded, VTK types, region).
#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "bindings.h"
#include "convert.h"
#include "hexdom/autopolycube/autopolycube.h"
#include "hexdom/common/format.h"
#include "hexdom/mesh/surface_check.h"
#include "hexdom/pipeline/mesh_surface.h"
#include "hexdom/pipeline/stretch.h"

namespace py = pybind11;

namespace hexdom::python {

namespace {

py::dict polycube_dict(const autopolycube::AutoPolycube& r) {
  py::dict d;
  d["structure"] = mesh_tuple(r.structure);
  d["patches"] = surface_tuple(r.patches);
  d["labels"] = surface_tuple(r.labels);
  d["polycube"] = surface_tuple(r.polycube);
  r.for_each_figure([&](const char* name, auto value) { d[name] = value; });
  return d;
}

const char* kAutopolycubeDoc =
    "Automatic polycube structure from a labelled surface (label 1..6 = +X, -X, +Y, -Y, +Z, -Z per\n"
    "triangle, as segment() gives): the charts are flattened onto axis-aligned planes on a grid of spacing\n"
    "h = size * 2^level (size 0: bounding-box diagonal / 30), every grid cell inside becomes a hex block (a\n"
    "prism under a sliver strip chart along a knife edge), and the surface is re-split along the grid lines\n"
    "into one patch per boundary face of the blocks, so that generate()\n"
    "takes the pair unchanged. Labellings that cannot be a polycube are repaired by relabelling the smallest\n"
    "chart involved (at most max_relabels; charts blamed for a fold only up to max_relabel_area of the\n"
    "surface). Returns a dict: structure (V, cells, types, region), patches (V, F, patch), labels (the\n"
    "repaired labelling on the surface the map used), polycube (V, F, label at polycube positions), and the\n"
    "figures cell, charts, relabelled, chords, planes, pushed, squares, blocks, boundary_vertices,\n"
    "interior_vertices, slivers, prism_blocks, tet_blocks, oblique_faces, apexes (apex caps added), apexes_collapsed\n"
    "(of them, under tet and prism blocks), widened (walls keep_widths moved), min_block_quality, inverted_blocks. keep_widths:\n"
    "walls of a hole facing each other across the void keep their distance in cells (False: least-squares plane\n"
    "offsets); collapse_apexes: the blocks under an apex cap collapse to tets and prisms (False: they stay hexes).\n"
    "frame: a 3 x 3 rotation (cube_frame's): the labels refer to its axes, x_frame = frame @ x; every result\n"
    "is in the input's coordinates. stretch: factors along the frame's axes (mesh_surface's stretch): the\n"
    "polycube is built on the labels stretched so (size in that space), every result mapped back. Raises\n"
    "GeometryError naming the charts when the labelling cannot be repaired, also when max_same_problem rounds in a\n"
    "row end in the very same problem (the repair is not converging).";

const char* kMeshSurfaceDoc =
    "Hex mesh of a closed surface with no manual step: segment (CVT, edge_weight) -> autopolycube (size,\n"
    "level, max_relabels) -> generate (level, relax_sweeps) -> improve (recommended sequence, boundary on\n"
    "the patch surface; skipped with improve=False). The surface's patch ids are CAD faces when there are\n"
    "several. Returns a dict: mesh and generated (V, cells, types, region), labels (V, F, label),\n"
    "polycube (the autopolycube dict), quality and generated_quality (hex, prism, tet, total_volume),\n"
    "seconds (segment, autopolycube, generate, improve), and the options of the candidate kept: level,\n"
    "edge_weight, keep_widths, collapse_apexes (segment with edge_weight, then autopolycube with level,\n"
    "keep_widths and collapse_apexes rebuild its polycube), frame (the cube_frame dict the labels and the\n"
    "polycube refer to: segment and autopolycube with its rotation rebuild them; align=False: the model's\n"
    "axes; frame: this 3 x 3 rotation instead of the one the faces fit), stretch (the factors along the\n"
    "frame's axes a thin part was stretched by for those stages: segment, autopolycube and mesh_structure\n"
    "with frame and stretch rebuild them; ones: not stretched) and choice (them as one line of text).\n"
    "method: \"polycube\", \"overlay\" (a grid laid over the part, which meshes any closed surface) or \"auto\"\n"
    "(the polycube, and the overlay too when the polycube fails or misses a target; the better kept). The\n"
    "dict's method names the path that made the mesh, polycube_note why the overlay was tried (empty when it\n"
    "was not), budget_passed whether the polycube path's time budget cut it short, stage the stage that ran\n"
    "last, solids the solids meshed (each its own region when more than one), touching the pairs of them\n"
    "(1-based) that touch, warnings what the run warned of (the lines `hexdom mesh` prints as warnings: a\n"
    "shell turned around, solids touching). Inverted cells left are reported, not raised; an error raised\n"
    "carries what the finished stages made as its attribute partial (this dict).\n";

}  // namespace

const char* const kPolycubeSecondsDoc =
    "polycube_seconds: the polycube path's time budget in seconds (0: no limit; None: the default, 20 s under\n"
    "\"auto\", no limit under \"polycube\"). auto: once it has passed, the polycube path stops (the improvement\n"
    "ends its round, no further candidate is tried) and, without a mesh that meets the targets, the overlay\n"
    "runs; polycube_note then names the budget. polycube: given, it raises TimeoutError (an Error) when it\n"
    "passes before there is a mesh.";

const char* const kSizeBoundsDoc =
    "\nmax_size, min_size: bounds on the element size (0: none), as `hexdom mesh --max-size / --min-size`: the\n"
    "size (given or default) is brought within them, and cells made thinner for a thin part are not made\n"
    "shorter than min_size. cells_across: cells across a part thin along an axis (0: cubic cells).\n"
    "face_sizes: {face number: size}, cell sizes on faces (FreeCAD's Face<number>; for a surface, its patch\n"
    "ids), as `hexdom mesh --face-size`: each path refines by thirds near those faces (auto keeps the mesh\n"
    "within 20% of more sizes; run['local_size_ratios']); InputError for a face the part lacks.\n"
    "growth_rate: how fast the cells grow from those sizes back to the element size, per cell, in (1, 3]\n"
    "(`hexdom mesh --growth-rate`).";

const char* const kOrderDoc =
    "\norder: 1 (hex8, wedge6, tet4) or 2 (hex20, wedge15, tet10: the mesh's cells then have 20 columns, VTK's\n"
    "quadratic order, types 25 / 26 / 24), as `hexdom mesh --order`: a node on every cell edge, those of the\n"
    "boundary on the input surface (mesh_cad: on the B-rep), pulled back towards the edge's midpoint only where\n"
    "a cell would lose quality; the dict's second_order says how many (None for order 1).";

const char* const kPillowCurvesDoc =
    "\npillow_curves: the overlay path lays a sheet of wedges along each curve, so that every boundary face lies\n"
    "on one face (a face load in FreeCAD takes them all), as `hexdom mesh --pillow-curves`.";

const char* const kTimeLimitDoc =
    "\ntime_limit: seconds the whole call may take (0: no limit), as `hexdom mesh --time-limit`: past it the call\n"
    "stops within a fraction of a second and raises _hexdom.TimeoutError naming the step it was in.";

py::dict second_order_dict(const optimize::SecondOrderReport& so) {
  py::dict o;
  o["boundary_mid_nodes"] = so.boundary_mid_nodes;
  o["edge_targets"] = so.edge_targets;
  o["face_targets"] = so.face_targets;
  o["max_offset"] = so.max_offset;
  o["diagonal"] = so.diagonal;
  o["placed"] = so.curve.placed;
  o["shortened"] = so.curve.shortened;
  o["straight"] = so.curve.straight;
  o["max_gap"] = so.curve.max_gap;
  o["worst_sj"] = so.curve.worst_sj;
  o["inverted"] = so.curve.inverted;
  o["seconds"] = so.seconds;
  return o;
}

py::dict run_dict(const pipeline::MeshSurfaceRun& r) {
  py::dict d;
  d["mesh"] = mesh_tuple(r.mesh);
  d["generated"] = mesh_tuple(r.generated);
  d["labels"] = surface_tuple(r.labels);
  d["polycube"] = polycube_dict(r.polycube);
  d["quality"] = report_dict(r.quality);
  d["generated_quality"] = report_dict(r.generated_quality);
  d["seconds"] = std::vector<double>(r.seconds, r.seconds + 4);
  d["level"] = r.level;
  d["edge_weight"] = r.edge_weight;
  d["keep_widths"] = r.keep_widths;
  d["collapse_apexes"] = r.collapse_apexes;
  d["choice"] = pipeline::choice_text(r);
  d["method"] = pipeline::method_name(r.method);
  d["polycube_note"] = r.polycube_note;
  d["local_size_ratios"] = r.local_fit.ratio;
  std::vector<bool> met;
  for (double x : r.local_fit.ratio) met.push_back(pipeline::LocalSizeFit::within(x));
  d["local_size_met"] = met;
  const std::vector<char> face_only = pipeline::snap_face_only(r);
  d["face_only"] = std::vector<int>(face_only.begin(), face_only.end());
  d["budget_passed"] = r.budget_passed;
  d["frame"] = frame_dict(r.frame);
  d["stretch"] = std::vector<double>{r.stretch(0), r.stretch(1), r.stretch(2)};
  d["stage"] = r.stage;
  d["solids"] = std::max<size_t>(1, r.solids.size());
  py::list touching;
  for (const auto& [a, b] : r.touching) touching.append(py::make_tuple(a, b));
  d["touching"] = touching;
  d["second_order"] = r.mesh.second_order() ? py::object(second_order_dict(r.second_order)) : py::object(py::none());
  return d;
}

pipeline::MeshSurfaceOptions mesh_surface_options(double size, int level, double edge_weight, int max_relabels,
                                                      int relax_sweeps, bool improve, bool align,
                                                      const std::optional<Eigen::Matrix3d>& frame, const std::string& method,
                                                      std::optional<double> polycube_seconds, double max_size,
                                                      double min_size, double cells_across,
                                                      const std::map<int, double>& face_sizes, double growth_rate,
                                                      int order, double time_limit, bool pillow_curves) {
  pipeline::MeshSurfaceOptions opt;
  if (!(time_limit >= 0)) throw InputError("time_limit must be 0 (no limit) or positive");
  opt.time_limit = time_limit;
  pipeline::check_order(order);
  opt.order = order;
  opt.overlay.growth_rate = growth_rate;
  opt.overlay.pillow_curves = pillow_curves;
  for (const auto& [face, size] : face_sizes) {
    if (face < 1 || !(size > 0))
      throw InputError(fmt("face_sizes {%.0f: %g}: the face number must be at least 1 and the size positive", double(face), size));
    opt.overlay.local_sizes.push_back({face, size});
  }
  if (!(cells_across >= 0)) throw InputError("cells_across must not be negative (0: cubic cells)");
  opt.max_size = max_size;
  opt.min_size = min_size;
  opt.across_thin = cells_across;
  pipeline::check_size_bounds(opt);  // before any work
  opt.method = pipeline::method_from_name(method);
  if (polycube_seconds) {
    if (!(*polycube_seconds >= 0)) throw InputError("polycube_seconds must be 0 (no limit) or positive");
    opt.polycube_seconds = *polycube_seconds;
    if (opt.method == pipeline::Method::Polycube) opt.deadline = Deadline::in(*polycube_seconds);
  }
  opt.align = align;
  if (frame) opt.segment.frame = opt.polycube.frame = checked_rotation(*frame);
  opt.size = size;
  opt.level = level;
  opt.segment.edge_weight = edge_weight;
  opt.polycube.max_relabels = max_relabels;
  opt.relax_sweeps = relax_sweeps;
  opt.improve = improve;
  return opt;
}

void bind_auto(py::module_& m) {
  m.def("autopolycube",
        [](const RefV& V, const RefF& F, const RefI& label, double size, int level, int max_relabels, int max_attempts,
           double max_relabel_area, int untangle_rounds, bool keep_widths, bool collapse_apexes,
           std::optional<Eigen::Matrix3d> frame, std::optional<Eigen::Vector3d> stretch, int max_same_problem) {
          mesh::SurfaceMesh s = surface_of(V, F, label);
          autopolycube::AutoPolycubeOptions opt;
          if (frame) opt.frame = checked_rotation(*frame);
          const std::optional<pipeline::Stretch> st = into_stretched_frame(s, opt.frame, frame, stretch);
          opt.size = size;
          opt.level = level;
          opt.max_relabels = max_relabels;
          opt.max_attempts = max_attempts;
          if (max_same_problem < 1) throw GeometryError("max_same_problem must be at least 1");
          opt.max_same_problem = max_same_problem;
          opt.max_relabel_area = max_relabel_area;
          opt.untangle_rounds = untangle_rounds;
          opt.keep_widths = keep_widths;
          opt.collapse_apexes = collapse_apexes;
          autopolycube::AutoPolycube r;
          {
            py::gil_scoped_release nogil;
            r = autopolycube::autopolycube(s, opt);
          }
          if (st) pipeline::map_polycube(r, *st, false);
          return polycube_dict(r);
        },
        py::arg("V"), py::arg("F"), py::arg("label"), py::arg("size") = 0.0, py::arg("level") = 1,
        py::arg("max_relabels") = 200, py::arg("max_attempts") = 20, py::arg("max_relabel_area") = 0.03,
        py::arg("untangle_rounds") = 50, py::arg("keep_widths") = true, py::arg("collapse_apexes") = true,
        py::arg("frame") = py::none(), py::arg("stretch") = py::none(), py::arg("max_same_problem") = 3, kAutopolycubeDoc);

  m.def("check_surface",
        [](const RefV& V, const RefF& F, const RefI& patch, const std::string& name, bool self_intersection,
           bool several_solids) {
          mesh::SurfaceMesh s = surface_of(V, F, patch);
          mesh::SurfaceCheckOptions opt;
          opt.self_intersection = self_intersection;
          opt.several_solids = several_solids;
          mesh::SurfaceCheck r;
          {
            py::gil_scoped_release nogil;
            r = mesh::check_solid_surface(s, name, opt);
          }
          py::dict d;
          d["surface"] = surface_tuple(s);
          d["shells"] = r.shells;
          d["cavities"] = r.cavities;
          d["flipped_shells"] = r.flipped_shells;
          d["warnings"] = r.warnings;
          d["solids"] = r.solids;
          py::list touching;
          for (const auto& [a, b] : r.touching) touching.append(py::make_tuple(a, b));
          d["touching"] = touching;
          return d;
        },
        py::arg("V"), py::arg("F"), py::arg("patch"), py::arg("name") = "the surface", py::arg("self_intersection") = true,
        py::arg("several_solids") = false,
        "The checks every meshing path makes on its input surface first (mesh::check_solid_surface): closed and\n"
        "2-manifold, consistently oriented, no two triangles crossing or lying on each other, one solid (its\n"
        "cavities nested one deep), or with several_solids any number of solids. A shell facing the wrong way (an\n"
        "inside-out export, a cavity facing out of it) is turned around. Returns a dict: surface (V, F, patch with\n"
        "those shells turned), shells, cavities, flipped_shells, solids, touching (pairs of solids, 1-based, whose\n"
        "surfaces lie on each other), warnings (one line per shell turned, per pair touching, for slight folds).\n"
        "Raises GeometryError naming an edge, or two crossing triangles and a point (1-based), or the separate\n"
        "solids; `name` prefixes the messages.");

  m.def("mesh_structure",
        [](const RefV& V, const RefF& F, const RefI& patch, const Eigen::MatrixXd& structure_V, const CellArray& structure_cells,
           const Eigen::VectorXi& structure_types, int level, bool improve, int relax_sweeps, int threads,
           std::optional<Eigen::Matrix3d> frame, std::optional<Eigen::Vector3d> stretch) {
          const mesh::SurfaceMesh patches = surface_of(V, F, patch);
          const mesh::Mesh structure = make_mesh(structure_V, structure_cells, structure_types, std::nullopt);
          pipeline::MeshSurfaceOptions opt;
          opt.level = level;
          opt.improve = improve;
          opt.relax_sweeps = relax_sweeps;
          opt.threads = threads;
          Warnings warnings;
          opt.log = warnings.callback();
          pipeline::MeshSurfaceRun r;
          {
            py::gil_scoped_release nogil;
            if (const std::optional<pipeline::Stretch> st = stretch_arg(frame, stretch))
              pipeline::generate_and_improve_stretched(patches, structure, *st, opt, r);
            else
              pipeline::generate_and_improve(patches, structure, opt, r);
          }
          py::dict d = run_dict(r);
          d["warnings"] = warnings.lines();
          return d;
        },
        py::arg("V"), py::arg("F"), py::arg("patch"), py::arg("structure_V"), py::arg("structure_cells"),
        py::arg("structure_types"), py::arg("level") = pipeline::MeshSurfaceOptions{}.level,
        py::arg("improve") = pipeline::MeshSurfaceOptions{}.improve,
        py::arg("relax_sweeps") = pipeline::MeshSurfaceOptions{}.relax_sweeps, py::arg("threads") = 0,
        py::arg("frame") = py::none(), py::arg("stretch") = py::none(),
        "The polycube path's generation and improvement stages (pipeline::generate_and_improve) on a polycube\n"
        "structure (V, cells, types of its blocks) over its patch surface (V, F, patch), with `hexdom mesh`'s\n"
        "options: what mesh_surface runs after autopolycube. Returns mesh_surface's dict (mesh, generated,\n"
        "quality, generated_quality, seconds, level; no labels nor polycube) and warnings. stretch (with frame,\n"
        "as mesh_surface's run reports them): both meshed stretched so, the mesh mapped back.");

  const py::handle module = m;
  using pipeline::method_name;
  const pipeline::MeshSurfaceOptions defaults;  // the keywords' defaults: `hexdom mesh`'s
  m.def("mesh_surface",
        [module](const RefV& V, const RefF& F, const RefI& patch, double size, int level, double edge_weight, int max_relabels,
           int relax_sweeps, bool improve, bool align, std::optional<Eigen::Matrix3d> frame, const std::string& method,
           std::optional<double> polycube_seconds, double max_size, double min_size, double cells_across,
           const std::map<int, double>& face_sizes, double growth_rate, int order, double time_limit, bool pillow_curves) {
          mesh::SurfaceMesh s = surface_of(V, F, patch);
          pipeline::MeshSurfaceOptions opt =
              mesh_surface_options(size, level, edge_weight, max_relabels, relax_sweeps, improve, align, frame, method,
                                   polycube_seconds, max_size, min_size, cells_across, face_sizes, growth_rate, order,
                                   time_limit, pillow_curves);
          Warnings warnings;
          opt.log = warnings.callback();
          pipeline::MeshSurfaceRun r;
          try {
            py::gil_scoped_release nogil;
            pipeline::mesh_surface(s, opt, &r);
          } catch (const Error& e) {
            py::dict partial = run_dict(r);  // what the finished stages made
            partial["warnings"] = warnings.lines();
            raise_with(module, e, "partial", partial);
          }
          py::dict d = run_dict(r);
          d["warnings"] = warnings.lines();
          return d;
        },
        py::arg("V"), py::arg("F"), py::arg("patch"), py::arg("size") = defaults.size, py::arg("level") = defaults.level,
        py::arg("edge_weight") = defaults.segment.edge_weight, py::arg("max_relabels") = defaults.polycube.max_relabels,
        py::arg("relax_sweeps") = defaults.relax_sweeps, py::arg("improve") = defaults.improve,
        py::arg("align") = defaults.align, py::arg("frame") = py::none(), py::arg("method") = method_name(defaults.method),
        py::arg("polycube_seconds") = py::none(), py::arg("max_size") = defaults.max_size,
        py::arg("min_size") = defaults.min_size, py::arg("cells_across") = defaults.across_thin,
        py::arg("face_sizes") = std::map<int, double>{}, py::arg("growth_rate") = defaults.overlay.growth_rate,
        py::arg("order") = defaults.order, py::arg("time_limit") = defaults.time_limit,
        py::arg("pillow_curves") = defaults.overlay.pillow_curves,
        (std::string(kMeshSurfaceDoc) + kPolycubeSecondsDoc + kSizeBoundsDoc + kOrderDoc + kTimeLimitDoc + kPillowCurvesDoc)
            .c_str());
}

}  // namespace hexdom::python
