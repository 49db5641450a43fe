// _hexdom's CAD functions: tessellation of a STEP/IGES/BREP file or of a BREP string (FreeCAD's
// shape.exportBrepToString()), the solid's volume and facts, and projection onto its faces.
// Wherever a `source` is taken it is either a file path or BREP text.
#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "bindings.h"
#include "hexdom/cad/project.h"
#include "hexdom/cad/read_shape.h"
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

const char* kTessellateDoc =
    "Closed, outward triangle surface of one solid for hexdom's stages: near-isotropic triangles of about\n"
    "`size` (0: bounding-box diagonal / 30), refined where the curvature needs it (`deflection`: largest\n"
    "chord distance, 0: size / 50; `angle`: largest turning angle in degrees), vertices on the B-rep, CAD\n"
    "edges kept as mesh edges. `min_size`: smallest target length from curvature (0: size / 20);\n"
    "`iterations`: remeshing sweeps; `solid`: 1-based solid of a multi-solid source (0: the first).\n"
    "Returns (V #V x 3 float64, F #F x 3 int32, face_id #F int32), face_id being the 1-based CAD face\n"
    "(FreeCAD's Face{face_id}). Raises InputError for unreadable input, GeometryError for a source that\n"
    "holds no closed solid.";

}  // namespace

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
}

}  // namespace hexdom::python
