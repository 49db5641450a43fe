// Labels and frames the workbench needs for its displays and defaults: labels from normals (the
// Segmentation's "Surface patches" method, Edit Patches' new patches) and the diagonal of a part's
// box square to its frame (Mesh Part's default size).
#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <optional>

#include "bindings.h"
#include "convert.h"
#include "hexdom/segmentation/axis_labels.h"
#include "hexdom/segmentation/cube_frame.h"
#include "hexdom/segmentation/labels_of_parts.h"

namespace py = pybind11;

namespace hexdom::python {

void bind_labels(py::module_& m) {
  m.def("nearest_label",
        [](const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>& normals) {
          Eigen::VectorXi out(normals.rows());
          for (Eigen::Index r = 0; r < normals.rows(); ++r)
            out(r) = segmentation::nearest_label(normals.row(r).transpose());
          return out;
        },
        py::arg("normals"),
        "Label 1..6 of the axis nearest each row of normals (#N x 3): the largest dot product with an axis,\n"
        "ties (and zero rows) going to the lower label.");

  m.def("labels_from_normals",
        [](const RefV& V, const RefF& F, std::optional<Eigen::VectorXi> patch, std::optional<Eigen::Matrix3d> frame,
           std::optional<Eigen::Vector3d> stretch) {
          if (patch && patch->size() != F.rows())
            throw GeometryError(std::to_string(patch->size()) + " patch ids for " + std::to_string(F.rows()) +
                                " triangles");
          mesh::SurfaceMesh s = surface_of(V, F, patch ? *patch : Eigen::VectorXi::Zero(F.rows()));
          Eigen::Matrix3d R = frame ? checked_rotation(*frame) : Eigen::Matrix3d::Identity();
          into_stretched_frame(s, R, frame, stretch);  // the normals of the stretched surface
          return segmentation::labels_from_normals(s, R, patch.has_value());
        },
        py::arg("V"), py::arg("F"), py::arg("patch") = py::none(), py::arg("frame") = py::none(),
        py::arg("stretch") = py::none(),
        "Label 1..6 (+X, -X, +Y, -Y, +Z, -Z) per triangle: the axis nearest its normal, or with patch the\n"
        "axis nearest the area-weighted normal of its patch (one label per patch). frame: a 3 x 3\n"
        "rotation whose axes the labels name (x_frame = frame @ x); None: the model's axes. stretch: factors\n"
        "along the frame's axes (mesh_surface's stretch): the normals of the surface stretched so.");

  m.def("frame_diagonal",
        [](const RefV& V, const RefF& F, const Eigen::Matrix3d& rotation) {
          const mesh::SurfaceMesh s = surface_of(V, F, Eigen::VectorXi::Zero(F.rows()));
          return segmentation::frame_diagonal(s, checked_rotation(rotation));
        },
        py::arg("V"), py::arg("F"), py::arg("rotation"),
        "Diagonal of the bounding box of the surface turned into the frame (x_frame = rotation @ x): what\n"
        "the default element size (diagonal / 30) is taken from.");
}

}  // namespace hexdom::python
