// _hexdom: numpy arrays in, numpy arrays out, over the HexDom core. Kept thin: every function
// converts, calls one core function with the GIL released, and converts back.
#include <memory>
#include <vector>

#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "bindings.h"
#include "convert.h"
#include "hexdom/common/error.h"
#include "hexdom/common/interrupt.h"
#include "hexdom/generation/generate.h"
#include "hexdom/optimize/improve.h"
#include "hexdom/io/k_file.h"
#include "hexdom/io/mesh_io.h"
#include "hexdom/mesh/mesh.h"
#include "hexdom/mesh/remesh_triangles.h"
#include "hexdom/quality/report.h"

namespace py = pybind11;
using namespace hexdom;

using namespace hexdom::python;

namespace {
// The error classes: _hexdom.Error, then each subclass with it as its Python base class.
void register_errors(py::module_& m) {
  static py::exception<Error> error(m, "Error", PyExc_RuntimeError);
  static py::exception<InputError> input_error(m, "InputError", error.ptr());
  static py::exception<GeometryError> geometry_error(m, "GeometryError", error.ptr());
  static py::exception<MeshingError> meshing_error(m, "MeshingError", error.ptr());
  // _hexdom.TimeoutError (not Python's builtin of that name): a time budget passed before a result.
  static py::exception<TimeoutError> timeout_error(m, "TimeoutError", error.ptr());
  // _hexdom.Interrupted: a call stopped through an Interrupt; not an Error (see common/interrupt.h).
  static py::exception<InterruptedError> interrupted(m, "Interrupted", PyExc_Exception);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InterruptedError& e) {
      PyErr_SetString(interrupted.ptr(), e.what());
    } catch (const InputError& e) {
      PyErr_SetString(input_error.ptr(), e.what());
    } catch (const GeometryError& e) {
      PyErr_SetString(geometry_error.ptr(), e.what());
    } catch (const MeshingError& e) {
      PyErr_SetString(meshing_error.ptr(), e.what());
    } catch (const TimeoutError& e) {
      PyErr_SetString(timeout_error.ptr(), e.what());
    } catch (const Error& e) {
      PyErr_SetString(error.ptr(), e.what());
    }
  });
}

}  // namespace

std::optional<pipeline::Stretch> python::stretch_arg(const std::optional<Eigen::Matrix3d>& frame,
                                                    const std::optional<Eigen::Vector3d>& stretch) {
  if (!stretch || *stretch == Eigen::Vector3d::Ones()) return std::nullopt;
  return pipeline::stretch_of(frame ? checked_rotation(*frame) : Eigen::Matrix3d::Identity(), *stretch);
}

std::optional<pipeline::Stretch> python::into_stretched_frame(mesh::SurfaceMesh& s, Eigen::Matrix3d& R,
                                                             const std::optional<Eigen::Matrix3d>& frame,
                                                             const std::optional<Eigen::Vector3d>& stretch) {
  std::optional<pipeline::Stretch> st = stretch_arg(frame, stretch);
  if (st) {
    s.V = pipeline::stretched(s.V, *st);
    R = Eigen::Matrix3d::Identity();
  }
  return st;
}

[[noreturn]] void python::raise_with(py::handle module, const Error& e, const char* name, py::object value) {
  const char* cls = dynamic_cast<const InputError*>(&e)      ? "InputError"
                    : dynamic_cast<const GeometryError*>(&e) ? "GeometryError"
                    : dynamic_cast<const MeshingError*>(&e)  ? "MeshingError"
                    : dynamic_cast<const TimeoutError*>(&e)  ? "TimeoutError"
                                                             : "Error";
  py::object type = module.attr(cls);
  py::object error = type(e.what());
  error.attr(name) = std::move(value);
  PyErr_SetObject(type.ptr(), error.ptr());
  throw py::error_already_set();
}

LogCallback python::Warnings::callback() {
  return [this](int level, const std::string& message) {
    if (level < 1) return;
    const std::lock_guard<std::mutex> lock(mutex_);
    lines_.push_back(message);
  };
}

std::vector<std::string> python::Warnings::lines() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return lines_;
}

namespace {
// The scopes opened by `with interrupt:` on each thread, innermost last.
thread_local std::vector<std::unique_ptr<InterruptScope>> open_scopes;

void bind_interrupt(py::module_& m) {
  py::class_<Interrupt>(m, "Interrupt",
                        "A stop flag for core calls: the calls a thread makes inside `with interrupt:` raise "
                        "_hexdom.Interrupted within a fraction of a second once another thread calls "
                        "interrupt.cancel(); their inputs are left as they were.")
      .def(py::init<>())
      .def("cancel", &Interrupt::raise, "Stops the calls running under this interrupt (any thread).")
      .def_property_readonly("cancelled", &Interrupt::raised)
      .def("clear", &Interrupt::clear, "Lowers the flag for the next calls.")
      .def("__enter__", [](py::object self) {
        open_scopes.push_back(std::make_unique<InterruptScope>(&self.cast<const Interrupt&>()));
        return self;
      })
      .def("__exit__", [](const Interrupt&, py::args) {
        if (!open_scopes.empty()) open_scopes.pop_back();
        return false;
      });
}
}  // namespace

// face_sets: the boundary faces of a volume mesh tagged with their CAD faces (io::face_sets).
static void bind_face_sets(py::module_& m) {
  m.def("face_sets", [](const Eigen::MatrixXd& V, const CellArray& cells, const Eigen::VectorXi& types,
                        const Eigen::MatrixXd& SV, const Eigen::MatrixXi& SF, const Eigen::VectorXi& patch,
                        const std::optional<CellArray>& node_faces) {
    mesh::Mesh msh = make_mesh(V, cells, types, std::nullopt);
    io::FaceSets f;
    {
      py::gil_scoped_release nogil;
      f = io::face_sets(msh, mesh::SurfaceMesh{SV, SF, patch}, node_faces ? lists_of(*node_faces) : std::vector<std::vector<int>>{});
    }
    const Eigen::Index n = static_cast<Eigen::Index>(f.faces.size());
    CellArray nodes = CellArray::Constant(n, msh.second_order() ? 8 : 4, -1);
    Eigen::VectorXi cell(n), local(n), tag(n);
    for (Eigen::Index i = 0; i < n; ++i) {
      const mesh::BoundaryFace& b = f.faces[i];
      const std::vector<int> own = mesh::face_nodes(msh, b);
      for (size_t j = 0; j < own.size(); ++j) nodes(i, j < static_cast<size_t>(b.n) ? j : 4 + j - b.n) = own[j];
      cell(i) = b.cell, local(i) = b.local, tag(i) = f.tag[i];
    }
    py::dict sets;
    for (const auto& [k, v] : f.nodes) sets[py::int_(k)] = Eigen::VectorXi(Eigen::Map<const Eigen::VectorXi>(v.data(), v.size()));
    return py::make_tuple(nodes, cell, local, tag, sets);
  }, py::arg("V"), py::arg("cells"), py::arg("types"), py::arg("surface_V"), py::arg("surface_F"), py::arg("face_id"),
  py::arg("node_faces") = py::none(),
  "The boundary faces of a volume mesh, each with the CAD face id it lies on, and the nodes of each CAD\n"
  "face (io::face_sets). node_faces: #V x k, -1 padded, the CAD faces each boundary node lies on (the\n"
  "snap's 'faces'), or None: each face then takes the face_id of the surface triangle nearest its centre\n"
  "(the tessellation the mesh was made from). Returns (nodes #B x 4, corners outward, -1 padded for a\n"
  "triangle; #B x 8 for a second-order mesh, the mid-edge nodes of edges k..k+1 in columns 4..; cell #B;\n"
  "local face #B in VTK's numbering; face id #B, 0 where none; {face id: its nodes, increasing}).");
}

PYBIND11_MODULE(_hexdom, m) {
  m.doc() = "HexDom core: hex-dominant meshing by polycubes (numpy in, numpy out)";
  m.attr("__version__") = HEXDOM_VERSION;

  register_errors(m);
  bind_interrupt(m);

  m.def("read_mesh", [](const std::string& path) {
    mesh::Mesh r;
    { py::gil_scoped_release nogil; r = io::read_mesh(path); }
    return mesh_tuple(r);
  }, py::arg("path"),
  "Reads .k, .vtk, .vtu, .inp, .msh, .stl or .obj. Returns (V #V x 3, cells #C x 8 with -1 padding (#C x 20 for a\n"
  "second-order mesh), VTK types #C, region #C).");

  m.def("read_k", [](const std::string& path) {
    io::KFile k;
    { py::gil_scoped_release nogil; k = io::read_k(path); }
    return py::make_tuple(k.mesh.V, k.mesh.cells, k.mesh.types, k.mesh.region, k.node_ids, k.element_ids);
  }, py::arg("path"), "Reads an LS-DYNA .k file: (V, cells, types, region, node_ids, element_ids).");

  m.def("read_surface", [](const std::string& path) {
    mesh::SurfaceMesh s;
    { py::gil_scoped_release nogil; s = io::read_surface(path); }
    return py::make_tuple(s.V, s.F, s.patch);
  }, py::arg("path"), "Reads a triangle surface: (V #V x 3, F #F x 3, patch #F).");

  m.def("write_mesh", [](const std::string& path, const Eigen::MatrixXd& V, const CellArray& cells,
                         const Eigen::VectorXi& types, const std::optional<Eigen::VectorXi>& region,
                         bool binary) {
    mesh::Mesh msh = make_mesh(V, cells, types, region);
    io::WriteOptions opt;
    opt.binary = binary;
    py::gil_scoped_release nogil;
    io::write_mesh(path, msh, opt);
  }, py::arg("path"), py::arg("V"), py::arg("cells"), py::arg("types"), py::arg("region") = py::none(),
     py::arg("binary") = false, "Writes .k, .vtk, .vtu, .inp, .stl or .obj (format by extension).");

  m.def("write_surface", [](const std::string& path, const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                            const std::optional<Eigen::VectorXi>& patch) {
    mesh::SurfaceMesh s{V, F, patch ? *patch : Eigen::VectorXi::Zero(F.rows())};
    mesh::Mesh msh = mesh::from_surface(s);
    mesh::validate(msh);
    py::gil_scoped_release nogil;
    io::write_mesh(path, msh);
  }, py::arg("path"), py::arg("V"), py::arg("F"), py::arg("patch") = py::none());

  m.def("remesh_triangles", [](const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const Eigen::VectorXi& patch,
                               double size, int iterations) {
    mesh::RemeshTrianglesOptions opt;
    opt.size = size;
    opt.iterations = iterations;
    mesh::SurfaceMesh out;
    {
      py::gil_scoped_release nogil;
      out = mesh::remesh_triangles(mesh::SurfaceMesh{V, F, patch}, opt);
    }
    return py::make_tuple(out.V, out.F, out.patch);
  }, py::arg("V"), py::arg("F"), py::arg("patch"), py::arg("size") = 0.0, py::arg("iterations") = 10,
  "Remeshes a closed, outward triangle surface (V, F, face id per triangle) onto itself: near-equilateral\n"
  "triangles of about `size` (0: bounding-box diagonal / 30), vertices on the input triangles of their own\n"
  "face id, curves where two face ids meet and their corners kept. Returns (V, F, face_id). Raises InputError\n"
  "for an open or non-manifold surface (naming the edge) or a degenerate triangle.");

  bind_face_sets(m);

  m.def("cell_metrics", [](const Eigen::MatrixXd& V, const CellArray& cells, const Eigen::VectorXi& types) {
    mesh::Mesh msh = make_mesh(V, cells, types, std::nullopt);
    quality::CellMetrics q;
    { py::gil_scoped_release nogil; q = quality::compute_metrics(msh); }
    return py::make_tuple(q.scaled_jacobian, q.edge_ratio, q.volume);
  }, py::arg("V"), py::arg("cells"), py::arg("types"),
  "Per-cell (scaled_jacobian, edge_ratio, volume), Verdict's definitions; NaN for 2D cells.");

  m.def("quality_report", [](const Eigen::MatrixXd& V, const CellArray& cells, const Eigen::VectorXi& types) {
    mesh::Mesh msh = make_mesh(V, cells, types, std::nullopt);
    quality::QualityReport r;
    { py::gil_scoped_release nogil; r = quality::quality_report(msh); }
    return report_dict(r);
  }, py::arg("V"), py::arg("cells"), py::arg("types"),
  "Dict with keys hex, prism, tet (count, sj_min, sj_mean, inverted, edge_ratio_min, edge_ratio_max, volume, histogram) and total_volume.");

  m.def("generate", [](const Eigen::MatrixXd& SV, const Eigen::MatrixXi& SF, const Eigen::VectorXi& patch,
                       const Eigen::MatrixXd& TV, const CellArray& Tcells, const Eigen::VectorXi& Ttypes,
                       int level, int relax_sweeps, double snap_tolerance, bool untangle, int threads) {
    mesh::SurfaceMesh surface{SV, SF, patch};
    mesh::Mesh structure = make_mesh(TV, Tcells, Ttypes, std::nullopt);
    generation::GenerateOptions opt;
    opt.level = level;
    opt.relax_sweeps = relax_sweeps;
    opt.snap_tolerance = snap_tolerance;
    opt.untangle = untangle;
    opt.threads = threads;
    mesh::Mesh r;
    { py::gil_scoped_release nogil; r = generation::generate(surface, structure, opt); }
    return mesh_tuple(r);
  }, py::arg("surface_V"), py::arg("surface_F"), py::arg("patch"), py::arg("structure_V"),
     py::arg("structure_cells"), py::arg("structure_types"), py::arg("level") = 2,
     py::arg("relax_sweeps") = 10, py::arg("snap_tolerance") = 1e-4, py::arg("untangle") = true, py::arg("threads") = 0,
  "Hex-dominant mesh from a segmented surface (V, F, patch id per triangle) and a polycube structure\n"
  "(V, cells, types of hex/prism/tet blocks): 8^level cells per block. Returns (V, cells, types, region).\n"
  "untangle: after the plain relaxation, untangle the cells it leaves inverted (boundary nodes may slide within\n"
  "the surface). threads: for the patch maps, block interiors and cells (0: one per hardware thread; same result).");

  m.def("improve", [](const Eigen::MatrixXd& V, const CellArray& cells, const Eigen::VectorXi& types,
                      const std::optional<Eigen::VectorXi>& region, bool pillow, int smooth, int optimize,
                      double feature_angle, const std::vector<int>& sharp_nodes,
                      const std::optional<Eigen::MatrixXd>& surface_V, const std::optional<Eigen::MatrixXi>& surface_F,
                      double max_edge_ratio) {
    mesh::Mesh msh = make_mesh(V, cells, types, region);
    optimize::ImproveOptions opt;
    opt.pillow = pillow;
    opt.smooth = smooth;
    opt.optimize = optimize;
    opt.feature_angle = feature_angle;
    opt.sharp_nodes = sharp_nodes;
    opt.max_edge_ratio = max_edge_ratio;
    if (surface_V && surface_F) {
      opt.surface.V = *surface_V;
      opt.surface.F = *surface_F;
      opt.surface.patch = Eigen::VectorXi::Zero(surface_F->rows());
    }
    optimize::ImproveResult r;
    { py::gil_scoped_release nogil; r = optimize::improve(msh, opt); }
    return py::make_tuple(r.mesh.V, r.mesh.cells, r.mesh.types, r.mesh.region);
  }, py::arg("V"), py::arg("cells"), py::arg("types"), py::arg("region") = py::none(), py::arg("pillow") = false,
     py::arg("smooth") = 0, py::arg("optimize") = 0, py::arg("feature_angle") = 35.0,
     py::arg("sharp_nodes") = std::vector<int>{}, py::arg("surface_V") = py::none(), py::arg("surface_F") = py::none(),
     py::arg("max_edge_ratio") = 0.0,
  "Pillowing, smoothing and Jacobian optimisation; with no stage set, the recommended sequence.\n"
  "Boundary nodes stay on the given surface (or the mesh's own boundary). max_edge_ratio > 0: then the\n"
  "nodes of cells above that edge ratio move to lower it, no cell at or above 0.3 taken below it, each\n"
  "type's worst scaled Jacobian kept, then lowered in two steps towards 0.3 while cells stay above it.\n"
  "Returns (V, cells, types, region).");

  python::bind_segmentation(m);
  python::bind_polycube(m);
  python::bind_cad(m);
  python::bind_auto(m);
  python::bind_labels(m);
}
