// _hexdom's segmentation functions: CVT labelling, the polycube check, the polycube boundary and
// patch editing. Surfaces come in as (V #V x 3, F #F x 3, patch #F); labels are 1..6 (+X, -X, +Y,
// -Y, +Z, -Z), patch numbers 1-based, vertex and triangle indices 0-based.
#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "bindings.h"
#include "convert.h"
#include "hexdom/segmentation/axis_labels.h"
#include "hexdom/segmentation/check_patches.h"
#include "hexdom/segmentation/cube_frame.h"
#include "hexdom/segmentation/edit_patches.h"
#include "hexdom/segmentation/polycube_boundary.h"
#include "hexdom/segmentation/read_manual_labels.h"
#include "hexdom/segmentation/segment_cvt.h"
#include "hexdom/segmentation/segmentation_stats.h"

namespace py = pybind11;

namespace hexdom::python {

namespace {

py::array_t<double> vec3(const Eigen::Vector3d& v) {
  py::array_t<double> a(3);
  for (int i = 0; i < 3; ++i) a.mutable_at(i) = v(i);
  return a;
}

py::dict stats_dict(const segmentation::SegmentationStats& st) {
  py::dict d;
  d["patches"] = st.patches;
  d["small_patches"] = st.small_patches;
  d["boundary_length"] = st.boundary_length;
  d["teeth"] = st.teeth;
  d["max_angle"] = st.max_angle;
  d["axis_fraction"] = st.axis_fraction;
  d["label_axis_fraction"] = std::vector<double>(st.label_axis_fraction.begin(), st.label_axis_fraction.end());
  d["label_area"] = std::vector<double>(st.label_area.begin(), st.label_area.end());
  return d;
}

const char* kSegmentDoc =
    "Polycube segmentation by CVT of the triangle normals with generators +-X, +-Y, +-Z: the classical\n"
    "energy (generators follow their regions' mean normals, at most `max_drift` degrees from their axis),\n"
    "then the edge-weighted energy d^2 = |n - g|^2/4 + 2 edge_weight (N - N_same)/N over the triangles\n"
    "within `ring` edge steps, which removes zig-zag boundaries (lambda = edge_weight; 0 skips it).\n"
    "respect_faces: None = when `patch` has more than one id (CAD faces): planar faces keep one label, a\n"
    "curved face whose largest label covers `face_majority` of its area takes it entirely, and the edge\n"
    "term counts only neighbours in the same face. manual: (triangle, label 1..6) rows, fixed.\n"
    "Returns a dict: label (#F, 1..6), classical (#F, after the first pass), generators (6 x 3), and\n"
    "classical_sweeps, edge_sweeps, classical_moves, edge_moves, respected_faces, faces, planar_faces,\n"
    "uniform_faces. frame: a 3 x 3 rotation (cube_frame's): the labels name its axes (x_frame = frame @ x).\n"
    "stretch: factors along the frame's axes (mesh_surface's stretch): the surface is segmented stretched so.\n"
    "Raises GeometryError for an open, non-manifold or degenerate surface.";

// segment, cube_frame, read_manual_labels, segmentation_stats: labelling a surface and its figures.
void bind_labelling(py::module_& m) {
  m.def("segment",
        [](const RefV& V, const RefF& F, const RefI& patch, double edge_weight, int classical_sweeps, int edge_sweeps,
           int min_moves, double max_drift, int ring, std::optional<bool> respect_faces, double planar_angle,
           double face_majority, std::optional<Eigen::Matrix<int, Eigen::Dynamic, 2, Eigen::RowMajor>> manual,
           std::optional<Eigen::Matrix3d> frame, std::optional<Eigen::Vector3d> stretch) {
          mesh::SurfaceMesh s = surface_of(V, F, patch);
          segmentation::CvtOptions opt;
          if (frame) opt.frame = checked_rotation(*frame);
          into_stretched_frame(s, opt.frame, frame, stretch);  // segmented there
          opt.edge_weight = edge_weight;
          opt.classical_sweeps = classical_sweeps;
          opt.edge_sweeps = edge_sweeps;
          opt.min_moves = min_moves;
          opt.max_drift = max_drift;
          opt.ring = ring;
          opt.respect_faces = !respect_faces ? segmentation::FaceMode::Auto
                              : *respect_faces ? segmentation::FaceMode::On
                                               : segmentation::FaceMode::Off;
          opt.planar_angle = planar_angle;
          opt.face_majority = face_majority;
          if (manual)
            for (int i = 0; i < manual->rows(); ++i) opt.manual.emplace_back((*manual)(i, 0), (*manual)(i, 1));
          segmentation::Segmentation r;
          {
            py::gil_scoped_release nogil;
            r = segmentation::segment_cvt(s, opt);
          }
          py::dict d;
          d["label"] = r.label;
          d["classical"] = r.classical;
          d["generators"] = Eigen::MatrixXd(r.generators);
          d["classical_sweeps"] = r.classical_sweeps;
          d["edge_sweeps"] = r.edge_sweeps;
          d["classical_moves"] = r.classical_moves;
          d["edge_moves"] = r.edge_moves;
          d["respected_faces"] = r.respected_faces;
          d["faces"] = r.faces;
          d["planar_faces"] = r.planar_faces;
          d["uniform_faces"] = r.uniform_faces;
          return d;
        },
        py::arg("V"), py::arg("F"), py::arg("patch"), py::arg("edge_weight") = 0.1, py::arg("classical_sweeps") = 50,
        py::arg("edge_sweeps") = 200, py::arg("min_moves") = 3, py::arg("max_drift") = 10.0, py::arg("ring") = 2,
        py::arg("respect_faces") = py::none(), py::arg("planar_angle") = 1.0, py::arg("face_majority") = 0.9,
        py::arg("manual") = py::none(), py::arg("frame") = py::none(), py::arg("stretch") = py::none(), kSegmentDoc);

  m.def("cube_frame",
        [](const RefV& V, const RefF& F, double min_gain) {
          mesh::SurfaceMesh s = surface_of(V, F, Eigen::VectorXi::Zero(F.rows()));
          segmentation::CubeFrameOptions opt;
          opt.min_gain = min_gain;
          segmentation::CubeFrame r;
          {
            py::gil_scoped_release nogil;
            r = segmentation::cube_frame(s, opt);
          }
          return frame_dict(r);
        },
        py::arg("V"), py::arg("F"), py::arg("min_gain") = 0.02,
        "The frame the triangle normals fit best: the rotation maximising the area-weighted mean of\n"
        "sum_k (R n)_k^4 (1 for a box square to the axes), or the identity when it gains no more than\n"
        "min_gain over the model's own axes. Returns a dict: rotation (3 x 3, x_frame = rotation @ x), fit,\n"
        "fit_identity, angle (degrees), axis, turned (bool). segment(frame=...) and autopolycube(frame=...)\n"
        "take the rotation.");

  m.def("read_manual_labels",
        [](const std::string& path) {
          auto pairs = segmentation::read_manual_labels(path);
          Eigen::Matrix<int, Eigen::Dynamic, 2, Eigen::RowMajor> a(static_cast<int>(pairs.size()), 2);
          for (size_t i = 0; i < pairs.size(); ++i) a.row(static_cast<int>(i)) << pairs[i].first, pairs[i].second;
          return a;
        },
        py::arg("path"),
        "Reads the original's manual override file ('triangle label', both 0-based). Returns #N x 2 rows\n"
        "(triangle 0-based, label 1..6). Raises InputError naming the file and line.");

  m.def("segmentation_stats",
        [](const RefV& V, const RefF& F, const RefI& label, double max_angle) {
          mesh::SurfaceMesh s = surface_of(V, F, label);
          segmentation::check_surface(s);
          return stats_dict(segmentation::segmentation_stats(s, label, max_angle));
        },
        py::arg("V"), py::arg("F"), py::arg("label"), py::arg("max_angle") = 55.0,
        "Figures of a labelling (1..6 per triangle): patches, small_patches (< 10 triangles), boundary_length,\n"
        "teeth (triangles with 2 or 3 neighbours of one other label: zig-zags), axis_fraction (area share within\n"
        "max_angle degrees of the label's axis), label_axis_fraction and label_area per label 1..6.");
}

// check_patches: the polycube conditions of a segmented surface.
void bind_check(py::module_& m) {
  m.def("check_patches",
        [](const RefV& V, const RefF& F, const RefI& patch, double opposite_angle, double corner_defect,
           double corner_angle, double turn_window, const std::vector<int>& triangular_ids) {
          mesh::SurfaceMesh s = surface_of(V, F, patch);
          segmentation::CheckOptions opt;
          opt.opposite_angle = opposite_angle;
          opt.corner_defect = corner_defect;
          opt.corner_angle = corner_angle;
          opt.turn_window = turn_window;
          opt.triangular_ids = triangular_ids;
          segmentation::PatchCheck c;
          {
            py::gil_scoped_release nogil;
            c = segmentation::check_patches(s, opt);
          }
          py::list patches, violations;
          for (const auto& p : c.patches) {
            py::dict d;
            d["patch"] = p.patch;
            d["id"] = p.id;
            d["orientation"] = p.orientation;
            d["orientation_name"] = segmentation::label_name(p.orientation);
            d["normal"] = vec3(p.normal);
            d["area"] = p.area;
            d["triangles"] = p.triangles;
            d["type"] = p.triangular ? "triangle" : "quad";
            d["curves"] = p.curves;
            d["loops"] = p.loops;
            d["euler"] = p.euler;
            d["corners"] = p.corners;
            d["neighbours"] = p.neighbours;
            patches.append(d);
          }
          for (const auto& v : c.violations) {
            py::dict d;
            d["kind"] = segmentation::kind_name(v.kind);
            d["patches"] = v.patches;
            d["vertex"] = v.vertex;
            d["location"] = vec3(v.location);
            d["message"] = v.message;
            violations.append(d);
          }
          py::dict d;
          d["valid"] = c.is_valid();
          d["patches"] = patches;
          d["corners"] = c.corners;
          d["curves"] = c.curves;
          d["violations"] = violations;
          return d;
        },
        py::arg("V"), py::arg("F"), py::arg("patch"), py::arg("opposite_angle") = 135.0, py::arg("corner_defect") = 70.0,
        py::arg("corner_angle") = 0.0, py::arg("turn_window") = 3.0, py::arg("triangular_ids") = std::vector<int>{},
        "Polycube conditions of a segmented surface (patch = connected region of one id): opposite orientations\n"
        "sharing a boundary, corners shared by fewer than 3 patches (branchings between 2 patches, closed curves\n"
        "without corners, sharp vertices with |angle defect| > corner_defect, and with corner_angle > 0 curves\n"
        "turning by more), quadrilateral patches without 4 curves / triangular ones without 3, patches that are\n"
        "not disks. Returns a dict: valid, patches (dicts: patch, id, orientation 1..6, orientation_name, normal,\n"
        "area, triangles, type, curves, loops, euler, corners, neighbours), corners, curves, violations (dicts:\n"
        "kind, patches, vertex, location, message). Raises GeometryError for an unfit surface.");
}

// polycube_boundary: corners, edges and faces of a segmented surface, with one shell per patch.
void bind_boundary(py::module_& m) {
  m.def("polycube_boundary",
        [](const RefV& V, const RefF& F, const RefI& patch) {
          mesh::SurfaceMesh s = surface_of(V, F, patch);
          segmentation::PolycubeBoundary b;
          mesh::Mesh shells;
          {
            py::gil_scoped_release nogil;
            b = segmentation::polycube_boundary(s);
            shells = segmentation::polycube_shells(b);
          }
          py::list edges, faces;
          for (const auto& e : b.edges) {
            py::dict d;
            d["corners"] = std::vector<int>{e.corners[0], e.corners[1]};
            d["patches"] = std::vector<int>{e.patches[0], e.patches[1]};
            d["path"] = e.path;
            edges.append(d);
          }
          for (const auto& f : b.faces) {
            py::dict d;
            d["patch"] = f.patch;
            d["id"] = f.id;
            d["corners"] = f.corners;
            faces.append(d);
          }
          py::dict d;
          d["corner_vertices"] = b.corner_vertices;
          d["corners"] = b.corners;
          d["edges"] = edges;
          d["faces"] = faces;
          d["shells"] = py::make_tuple(shells.V, shells.cells, shells.types, shells.region);
          return d;
        },
        py::arg("V"), py::arg("F"), py::arg("patch"),
        "Polycube boundary of a segmented surface, as the original's initial polycube files. Returns a dict:\n"
        "corner_vertices (0-based, ascending), corners (#C x 3), edges (dicts: corners, patches, path of\n"
        "vertices), faces (dicts: patch, id, corners counter-clockwise), shells (V, cells, types, region: one\n"
        "quad or triangle per patch over the corners). Raises GeometryError when a patch is not a disk with\n"
        "3 or 4 corners.");
}

// number_patches, reassign_triangles, merge_patches, split_patch: patch editing, each giving a new
// patch map.
void bind_patch_editing(py::module_& m) {
  m.def("number_patches",
        [](const RefV& V, const RefF& F, const RefI& patch) { return segmentation::number_patches(surface_of(V, F, patch)); },
        py::arg("V"), py::arg("F"), py::arg("patch"),
        "One id per connected region, 1..R in the order of each region's first triangle.");
  m.def("reassign_triangles",
        [](const RefV& V, const RefF& F, const RefI& patch, const std::vector<int>& triangles, int id) {
          return segmentation::reassign_triangles(surface_of(V, F, patch), triangles, id);
        },
        py::arg("V"), py::arg("F"), py::arg("patch"), py::arg("triangles"), py::arg("id") = 0,
        "New patch map: `triangles` (0-based) take patch id `id` (<= 0: a new id, the largest + 1).");
  m.def("merge_patches",
        [](const RefV& V, const RefF& F, const RefI& patch, int a, int b) {
          return segmentation::merge_patches(surface_of(V, F, patch), a, b);
        },
        py::arg("V"), py::arg("F"), py::arg("patch"), py::arg("a"), py::arg("b"),
        "New patch map: patch id b's triangles take id a. Raises GeometryError when they share no edge.");
  m.def("split_patch",
        [](const RefV& V, const RefF& F, const RefI& patch, int id, const std::vector<int>& path) {
          return segmentation::split_patch(surface_of(V, F, patch), id, path);
        },
        py::arg("V"), py::arg("F"), py::arg("patch"), py::arg("id"), py::arg("path"),
        "New patch map: patch id `id` cut along a path of vertices (0-based; consecutive ones joined by the\n"
        "shortest chain of the patch's interior edges); the part without the patch's first triangle gets a new\n"
        "id. Raises GeometryError when the path separates nothing.");
}

}  // namespace

void bind_segmentation(py::module_& m) {
  bind_labelling(m);
  bind_check(m);
  bind_boundary(m);
  bind_patch_editing(m);
}

}  // namespace hexdom::python
