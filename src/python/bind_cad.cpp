// _hexdom's CAD functions: tessellation of a STEP/IGES/BREP file or of a BREP string (FreeCAD's
// shape.exportBrepToString()), the solid's volume and facts, and projection onto its faces.
// Wherever a `source` is taken it is either a file path or BREP text.
#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "bindings.h"
#include "hexdom/common/format.h"
#include "convert.h"
#include "hexdom/cad/second_order.h"
#include "hexdom/pipeline/mesh_cad.h"
#include "hexdom/cad/project.h"
#include "hexdom/cad/read_shape.h"
#include "hexdom/cad/snap.h"
#include "hexdom/cad/tessellate.h"

namespace py = pybind11;

namespace hexdom::python {

namespace {

py::tuple tessellate_source(const std::string& source, bool brep, double size, double deflection, double angle,
                            double min_size, int iterations, int solid) {
  cad::TessellateOptions opt;
  opt.size = size;
  opt.deflection = deflection;
  opt.angle = angle;
  opt.min_size = min_size;
  opt.iterations = iterations;
  mesh::SurfaceMesh s;
  {
    py::gil_scoped_release nogil;
    cad::ReadOptions ro;
    ro.solid = solid;
    cad::Shape shape = brep ? cad::read_brep_string(source, ro) : cad::read_shape(source, ro);
    s = cad::tessellate(shape, opt);
  }
  return py::make_tuple(s.V, s.F, s.patch);
}

cad::Shape read_source(const std::string& source, int solid) {
  cad::ReadOptions ro;
  ro.solid = solid;
  return cad::read_shape_or_brep(source, ro);
}

py::dict snap_dict(const cad::SnapResult& r) {
  const cad::SnapReport& q = r.report;
  py::dict d;
  d["boundary_nodes"] = q.boundary_nodes;
  d["face_nodes"] = q.face_nodes;
  d["edge_nodes"] = q.edge_nodes;
  d["vertex_nodes"] = q.vertex_nodes;
  d["max_before"] = q.max_before;
  d["mean_before"] = q.mean_before;
  d["max_after"] = q.max_after;
  d["mean_after"] = q.mean_after;
  d["max_move"] = q.max_move;
  d["diagonal"] = q.diagonal;
  d["inverted_snapped"] = q.inverted_snapped;
  d["inverted"] = q.inverted;
  d["worst_sj_before"] = q.worst_sj_before;
  d["worst_sj_snapped"] = q.worst_sj_snapped;
  d["worst_sj"] = q.worst_sj;
  d["seconds_project"] = q.seconds_project;
  d["seconds_restore"] = q.seconds_restore;
  d["quality"] = report_dict(r.quality);
  Eigen::VectorXi kind(r.kind.size()), entity(r.entity.size());
  for (size_t i = 0; i < r.kind.size(); ++i) kind(i) = static_cast<int>(r.kind[i]), entity(i) = r.entity[i];
  d["kind"] = kind;
  d["entity"] = entity;
  d["faces"] = padded_lists(r.faces);
  return d;
}

const char* kTessellateDoc =
    "Closed, outward triangle surface of one solid for hexdom's stages: near-isotropic triangles of about\n"
    "`size` (0: bounding-box diagonal / 30), refined where the curvature needs it (`deflection`: largest\n"
    "chord distance, 0: size / 50; `angle`: largest turning angle in degrees), vertices on the B-rep, CAD\n"
    "edges kept as mesh edges. `min_size`: smallest target length from curvature (0: size / 20);\n"
    "`iterations`: remeshing sweeps; `solid`: 1-based solid of a multi-solid source (0: the first).\n"
    "Returns (V #V x 3 float64, F #F x 3 int32, face_id #F int32), face_id being the 1-based CAD face\n"
    "(FreeCAD's Face{face_id}). Raises InputError for unreadable input, GeometryError for a source that\n"
    "holds no closed solid.";

const char* kSnapDoc =
    "Puts the boundary nodes of a volume mesh (V, cells #C x 8 -1 padded, VTK types, region) exactly on the\n"
    "B-rep of `source` (CAD file path or BREP text; `solid` 1-based, 0: the first), classified with the CAD\n"
    "face ids of its tessellation (surface V, F, face_id as tessellate_* return them): a node among three\n"
    "CAD faces meeting at a vertex and within edge_tolerance x its shortest boundary edge of it goes onto\n"
    "the vertex, a node among faces sharing a CAD edge and that near it onto the edge, every other one onto\n"
    "the nearest of its faces (trimmed). Then the interior is smoothed (`smooth` passes) and optimised\n"
    "(`optimize` rounds) with the boundary held. Returns (mesh tuple, report dict): boundary_nodes,\n"
    "face_nodes, edge_nodes, vertex_nodes, max_before, mean_before, max_after, mean_after (each\n"
    "node's distance to the face, edge or vertex it is put on, before and after: at least its B-rep distance), max_move, diagonal, inverted_snapped, inverted, worst_sj_before, worst_sj_snapped,\n"
    "worst_sj, seconds_project, seconds_restore, quality (as quality_report), kind (#V: 0 interior, 1 face,\n"
    "2 edge, 3 vertex) and entity (#V: 1-based face / edge / vertex id, 0 inside).";

// mesh_cad's documentation, with polycube_seconds= as mesh_surface documents it.
std::string mesh_cad_doc() {
  return std::string(
      "A CAD part (file path or BREP text) meshed as `hexdom mesh` does: tessellate, mesh_surface (`method`:\n"
      "auto, polycube or overlay, as mesh_surface), snap onto\n"
      "the B-rep; when the tessellation's labelling defeats the automatic polycube or cells stay inverted, the\n"
      "B-rep is tessellated again with triangles of 0.97, 1.03, 0.94, 1.06 x the size (the first two for\n"
      "inverted cells; the polycube grid kept)\n"
      "and the better mesh kept. Returns a dict: surface (V, F, face_id of the tessellation kept), run (as\n"
      "mesh_surface returns it; mesh and quality after the snap), snap (as snap_to_brep's report, None without\n"
      "snap), tessellate_seconds, snap_seconds, tessellations, tessellation_factor, tessellation_size (its target triangle size),\n"
      "solids, touching and warnings (the lines `hexdom mesh` prints as warnings). A source with several solids (solid=0) has each meshed, solid k's cells in region k:\n"
      "surface, run and snap are then the whole part's, numbered as FreeCAD numbers the source's faces, edges\n"
      "and vertices (face_sizes and edge_sizes too), solids a dict per solid (the same numbers), touching the\n"
      "pairs (1-based) of solids that touch (their meshes do not conform there); with one solid, solids and\n"
      "touching are empty. Raises the first\n"
      "tessellation's error when none gives a mesh, with what the finished stages made as its attribute\n"
      "partial (this dict; partial[\"stage\"] the stage that failed).\n") + kPolycubeSecondsDoc +
      " The budget covers the polycube path on every tessellation of the call; once it has passed, no\n"
      "further tessellation is tried for the polycube.";
}

}  // namespace

py::dict cad_run_dict(const pipeline::MeshCadRun& r) {
  py::dict d;
  d["surface"] = surface_tuple(r.surface);
  d["run"] = run_dict(r.run);
  d["stage"] = r.run.stage;
  d["snap"] = r.snapped ? py::object(snap_dict(r.snap)) : py::object(py::none());
  d["tessellate_seconds"] = r.stats.seconds;
  d["snap_seconds"] = r.snap_seconds;
  d["tessellations"] = r.tessellations;
  d["tessellation_factor"] = r.tessellation_factor;
  d["tessellation_size"] = r.stats.size;
  return d;
}

// `hexdom mesh`: mesh_options (its defaults) and mesh_cad (its whole pipeline on a CAD part).
void bind_mesh_cad(py::module_& m) {
  const py::handle module = m;
  const pipeline::MeshCadOptions defaults;  // `hexdom mesh`'s: the keywords' defaults, mesh_options()
  m.def("mesh_options",
        [defaults] {
          const pipeline::MeshSurfaceOptions& o = defaults.mesh;
          py::dict d;
          d["size"] = o.size;
          d["level"] = o.level;
          d["method"] = pipeline::method_name(o.method);
          d["improve"] = o.improve;
          d["align"] = o.align;
          d["snap"] = defaults.snap;
          d["polycube_seconds"] = o.polycube_seconds;
          d["edge_weight"] = o.segment.edge_weight;
          d["max_relabels"] = o.polycube.max_relabels;
          d["relax_sweeps"] = o.relax_sweeps;
          d["threads"] = o.threads;
          d["max_size"] = o.max_size;
          d["min_size"] = o.min_size;
          d["cells_across"] = o.across_thin;
          d["growth_rate"] = o.overlay.growth_rate;
          d["pillow_curves"] = o.overlay.pillow_curves;
          d["order"] = o.order;
          d["time_limit"] = o.time_limit;
          d["target_sj"] = o.target_sj;
          d["target_volume"] = o.target_volume;
          d["target_edge_ratio"] = o.target_edge_ratio;
          return d;
        },
        "The defaults of `hexdom mesh`'s options (pipeline::MeshCadOptions, the CLI's defaults), by the keyword\n"
        "names of mesh_cad and mesh_surface: size (0: the bounding-box diagonal / 30), max_size, min_size (0: no\n"
        "bound), cells_across, growth_rate, order, level, method, improve,\n"
        "align, snap, polycube_seconds, time_limit, edge_weight, max_relabels, relax_sweeps, threads (0: one per core), and\n"
        "the targets the candidates are measured against: target_sj, target_volume, target_edge_ratio.");
  m.def("mesh_cad",
        [module](const std::string& source, double size, int solid, bool snap, int level, double edge_weight, int max_relabels,
           int relax_sweeps, bool improve, bool align, std::optional<Eigen::Matrix3d> frame, const std::string& method,
           std::optional<double> polycube_seconds, double max_size, double min_size, double cells_across,
           const std::map<int, double>& face_sizes, double growth_rate, const std::map<int, double>& edge_sizes, int order,
           double time_limit, bool pillow_curves) {
          pipeline::MeshCadOptions opt;
          for (const auto& [edge, size] : edge_sizes) {
            if (edge < 1 || !(size > 0))
              throw InputError(fmt("edge_sizes {%.0f: %g}: the edge number must be at least 1 and the size positive",
                                   double(edge), size));
            opt.edge_sizes.emplace_back(edge, size);
          }
          opt.tessellation.size = size;
          opt.tessellation.size_in_frame = align;
          opt.mesh = mesh_surface_options(size, level, edge_weight, max_relabels, relax_sweeps, improve, align, frame, method,
                                          polycube_seconds, max_size, min_size, cells_across, face_sizes, growth_rate, order,
                                          time_limit, pillow_curves);
          opt.snap = snap;
          Warnings warnings;
          opt.log = opt.mesh.log = warnings.callback();
          pipeline::MeshSolidsRun r;
          try {
            py::gil_scoped_release nogil;
            cad::ReadOptions ro;
            ro.log = opt.log;
            ro.solid = solid;
            const std::vector<cad::Shape> solids = cad::read_solids(source, ro);
            if (solids.size() > 1) {
              pipeline::mesh_cad_solids(solids, opt, &r);
            } else {
              r.solids.emplace_back();
              pipeline::mesh_cad_part(solids.front(), opt, &r.solids.back());
              r.part = std::move(r.solids.back());
              r.solids.clear();
            }
          } catch (const Error& e) {
            // Raised with what the finished stages made (error.partial: this dict, its run's
            // stage the one that failed), for the front ends that show the stages.
            py::dict partial = cad_run_dict(r.solids.empty() ? r.part : r.solids.back());
            partial["warnings"] = warnings.lines();
            raise_with(module, e, "partial", partial);
          }
          py::dict d = cad_run_dict(r.part);
          py::list solids, touching;
          for (const pipeline::MeshCadRun& s : r.solids) solids.append(cad_run_dict(s));
          for (const auto& [a, b] : r.touching) touching.append(py::make_tuple(a, b));
          d["solids"] = solids;
          d["touching"] = touching;
          d["warnings"] = warnings.lines();
          return d;
        },
        py::arg("source"), py::arg("size") = defaults.mesh.size, py::arg("solid") = 0, py::arg("snap") = defaults.snap,
        py::arg("level") = defaults.mesh.level, py::arg("edge_weight") = defaults.mesh.segment.edge_weight,
        py::arg("max_relabels") = defaults.mesh.polycube.max_relabels, py::arg("relax_sweeps") = defaults.mesh.relax_sweeps,
        py::arg("improve") = defaults.mesh.improve, py::arg("align") = defaults.mesh.align, py::arg("frame") = py::none(),
        py::arg("method") = pipeline::method_name(defaults.mesh.method),
        py::arg("polycube_seconds") = py::none(), py::arg("max_size") = defaults.mesh.max_size,
        py::arg("min_size") = defaults.mesh.min_size, py::arg("cells_across") = defaults.mesh.across_thin,
        py::arg("face_sizes") = std::map<int, double>{}, py::arg("growth_rate") = defaults.mesh.overlay.growth_rate,
        py::arg("edge_sizes") = std::map<int, double>{}, py::arg("order") = defaults.mesh.order,
        py::arg("time_limit") = defaults.mesh.time_limit, py::arg("pillow_curves") = defaults.mesh.overlay.pillow_curves,
        (mesh_cad_doc() + kSizeBoundsDoc +
         "\nedge_sizes: {edge number: size}, cell sizes along CAD edges (FreeCAD's Edge<number>), as `hexdom mesh "
         "--edge-size`." + kOrderDoc + kTimeLimitDoc + kPillowCurvesDoc)
            .c_str());
}

// second_order: a first-order mesh made second order on a B-rep or a surface.
void bind_second_order(py::module_& m) {
  m.def("second_order",
        [](const Eigen::MatrixXd& V, const CellArray& cells, const Eigen::VectorXi& types,
           const std::optional<Eigen::VectorXi>& region, const RefV& sV, const RefF& sF, const RefI& face_id,
           const std::optional<std::string>& source, const std::vector<int>& kind, const std::vector<int>& entity,
           int solid, double min_sj) {
          const mesh::Mesh mesh = make_mesh(V, cells, types, region);
          const mesh::SurfaceMesh surface = surface_of(sV, sF, face_id);
          optimize::CurveOptions curve;
          curve.min_sj = min_sj;
          mesh::Mesh out;
          optimize::SecondOrderReport report;
          if (source) {
            if (static_cast<int>(kind.size()) != mesh.num_nodes() || static_cast<int>(entity.size()) != mesh.num_nodes())
              throw InputError("second_order: kind and entity (snap_to_brep's) need " + std::to_string(mesh.num_nodes()) +
                               " entries each, got " + std::to_string(kind.size()) + " and " + std::to_string(entity.size()));
            std::vector<cad::SnapKind> kinds(kind.size());
            for (size_t i = 0; i < kind.size(); ++i) kinds[i] = static_cast<cad::SnapKind>(kind[i]);
            py::gil_scoped_release nogil;
            cad::SecondOrderResult r = cad::second_order_on_brep(read_source(*source, solid), mesh, kinds, entity, surface, curve);
            out = std::move(r.mesh);
            report = r.report;
          } else {
            py::gil_scoped_release nogil;
            out = optimize::second_order_on_surface(mesh, surface, curve, &report);
          }
          return py::make_tuple(mesh_tuple(out), second_order_dict(report));
        },
        py::arg("V"), py::arg("cells"), py::arg("types"), py::arg("region"), py::arg("surface_V"), py::arg("surface_F"),
        py::arg("face_id"), py::arg("source") = py::none(), py::arg("kind") = std::vector<int>{},
        py::arg("entity") = std::vector<int>{}, py::arg("solid") = 0, py::arg("min_sj") = optimize::CurveOptions{}.min_sj,
        "A first-order volume mesh made second order (hex20 / wedge15 / tet10, cells #C x 20 in VTK's quadratic\n"
        "order), as `hexdom mesh --order 2` makes it: a node on every cell edge, those of the boundary on the\n"
        "B-rep of `source` (file path or BREP text; kind and entity: snap_to_brep's report for this mesh, which\n"
        "CAD edge or vertex each boundary node is on) or, without a source, on the triangle surface; each moved\n"
        "back towards its edge's midpoint where a cell would fall below min(min_sj, its straight value).\n"
        "Returns ((V, cells, types, region), report: boundary_mid_nodes, edge_targets, face_targets, max_offset,\n"
        "diagonal, placed, shortened, straight, max_gap, worst_sj, inverted, seconds).");

}

void bind_cad(py::module_& m) {
  m.def("has_opencascade", &cad::has_opencascade, "True when _hexdom was built with OpenCASCADE (CAD import).");

  m.def("tessellate_file",
        [](const std::string& path, double size, double deflection, double angle, double min_size, int iterations,
           int solid) { return tessellate_source(path, false, size, deflection, angle, min_size, iterations, solid); },
        py::arg("path"), py::arg("size") = 0.0, py::arg("deflection") = 0.0, py::arg("angle") = 30.0,
        py::arg("min_size") = 0.0, py::arg("iterations") = 10, py::arg("solid") = 0,
        (std::string("Tessellates a .step/.stp, .iges/.igs or .brep/.brp file.\n") + kTessellateDoc).c_str());

  m.def("tessellate_brep",
        [](const std::string& brep, double size, double deflection, double angle, double min_size, int iterations,
           int solid) { return tessellate_source(brep, true, size, deflection, angle, min_size, iterations, solid); },
        py::arg("brep"), py::arg("size") = 0.0, py::arg("deflection") = 0.0, py::arg("angle") = 30.0,
        py::arg("min_size") = 0.0, py::arg("iterations") = 10, py::arg("solid") = 0,
        (std::string("Tessellates a shape given as BREP text (FreeCAD: shape.exportBrepToString()).\n") +
         kTessellateDoc).c_str());

  m.def("cad_volume",
        [](const std::string& source, int solid) {
          py::gil_scoped_release nogil;
          return cad::shape_volume(read_source(source, solid));
        },
        py::arg("source"), py::arg("solid") = 0,
        "Volume of the solid (OCCT GProp) of a CAD file path or BREP text.");

  m.def("cad_info",
        [](const std::string& source, int solid) {
          cad::ShapeInfo info;
          {
            py::gil_scoped_release nogil;
            info = cad::shape_info(read_source(source, solid));
          }
          py::dict d;
          d["faces"] = info.faces;
          d["edges"] = info.edges;
          d["vertices"] = info.vertices;
          d["shells"] = info.shells;
          d["volume"] = info.volume;
          d["area"] = info.area;
          d["bbox_min"] = Eigen::Vector3d(info.box.min());
          d["bbox_max"] = Eigen::Vector3d(info.box.max());
          std::vector<std::string> types;
          for (auto t : info.face_types) types.push_back(cad::surface_type_name(t));
          d["face_types"] = types;
          d["vertex_points"] = info.vertex_points;
          return d;
        },
        py::arg("source"), py::arg("solid") = 0,
        "Facts about the solid of a CAD file path or BREP text: dict with faces, edges, vertices, shells,\n"
        "volume, area, bbox_min, bbox_max, vertex_points (Vertex1, Vertex2, ... as rows) and face_types (surface type of Face1, Face2, ...: 'plane',\n"
        "'cylinder', 'cone', 'sphere', 'torus', 'bspline', ...).");

  m.def("project_to_face",
        [](const std::string& source, int face_id, const Eigen::MatrixXd& points, int solid) {
          cad::Projection r;
          {
            py::gil_scoped_release nogil;
            r = cad::project_to_face(read_source(source, solid), face_id, points);
          }
          return py::make_tuple(r.points, r.distance, r.param);
        },
        py::arg("source"), py::arg("face_id"), py::arg("points"), py::arg("solid") = 0,
        "Nearest points of the trimmed face Face{face_id} (1-based) to `points` (N x 3). Returns\n"
        "(points N x 3, distance N, uv N x 2). `source` is a CAD file path or BREP text.");

  m.def("project_to_edge",
        [](const std::string& source, int edge_id, const Eigen::MatrixXd& points, int solid) {
          cad::Projection r;
          {
            py::gil_scoped_release nogil;
            r = cad::project_to_edge(read_source(source, solid), edge_id, points);
          }
          return py::make_tuple(r.points, r.distance, Eigen::VectorXd(r.param.col(0)));
        },
        py::arg("source"), py::arg("edge_id"), py::arg("points"), py::arg("solid") = 0,
        "Nearest points of the edge Edge{edge_id} (1-based) to `points` (N x 3), ends included. Returns\n"
        "(points N x 3, distance N, curve parameter N).");

  m.def("project_to_shape",
        [](const std::string& source, const Eigen::MatrixXd& points, int solid) {
          cad::Projection r;
          {
            py::gil_scoped_release nogil;
            r = cad::project_to_shape(read_source(source, solid), points);
          }
          return py::make_tuple(r.points, r.distance, r.id);
        },
        py::arg("source"), py::arg("points"), py::arg("solid") = 0,
        "Nearest points of the solid's boundary to `points` (N x 3). Returns (points N x 3, distance N,\n"
        "face_id N), face_id the 1-based face each lies on.");

  m.def("snap_to_brep",
        [](const std::string& source, const Eigen::MatrixXd& V, const CellArray& cells, const Eigen::VectorXi& types,
           const std::optional<Eigen::VectorXi>& region, const RefV& sV, const RefF& sF, const RefI& face_id, int solid,
           double edge_tolerance, int smooth, int optimize, double max_edge_ratio, const std::vector<int>& face_only) {
          mesh::Mesh mesh = make_mesh(V, cells, types, region);
          const mesh::SurfaceMesh surface = surface_of(sV, sF, face_id);
          cad::SnapOptions opt;
          opt.edge_tolerance = edge_tolerance;
          opt.smooth = smooth;
          opt.optimize = optimize;
          opt.max_edge_ratio = max_edge_ratio;
          if (!face_only.empty() && static_cast<int>(face_only.size()) != mesh.num_nodes())
            throw InputError("snap_to_brep: face_only has " + std::to_string(face_only.size()) + " entries for " +
                             std::to_string(mesh.num_nodes()) + " nodes");
          opt.face_only.assign(face_only.begin(), face_only.end());
          cad::SnapResult r;
          {
            py::gil_scoped_release nogil;
            r = cad::snap_to_brep(read_source(source, solid), mesh, surface, opt);
          }
          return py::make_tuple(mesh_tuple(r.mesh), snap_dict(r));
        },
        py::arg("source"), py::arg("V"), py::arg("cells"), py::arg("types"), py::arg("region"), py::arg("surface_V"),
        py::arg("surface_F"), py::arg("face_id"), py::arg("solid") = 0, py::arg("edge_tolerance") = 0.25,
        py::arg("smooth") = 3, py::arg("optimize") = 20, py::arg("max_edge_ratio") = 0.0,
        py::arg("face_only") = std::vector<int>(), kSnapDoc);

  bind_second_order(m);
  bind_mesh_cad(m);
}

}  // namespace hexdom::python
