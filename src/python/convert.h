// Conversions between numpy arrays and the core's types, shared by every bind_<stage>.cpp.
// Surfaces come in as (V #V x 3, F #F x 3, patch #F); meshes as (V, cells #C x 8 -1 padded, VTK
// types, region); quality reports go out as dicts keyed hex / prism / tet.
#pragma once

#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <optional>
#include <string>
#include <vector>

#include "hexdom/common/error.h"
#include "hexdom/mesh/mesh.h"
#include "hexdom/quality/report.h"
#include "hexdom/segmentation/cube_frame.h"

namespace hexdom::python {

namespace py = pybind11;

using RefV = Eigen::Ref<const Eigen::MatrixXd>;
using RefF = Eigen::Ref<const Eigen::Matrix<int, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>;
using RefI = Eigen::Ref<const Eigen::VectorXi>;
using CellArray = mesh::CellMatrix;

/// A checked SurfaceMesh; InputError names the first bad shape or index.
inline mesh::SurfaceMesh surface_of(const RefV& V, const RefF& F, const RefI& patch) {
  if (V.cols() != 3) throw InputError("V must be #V x 3, got " + std::to_string(V.cols()) + " columns");
  if (F.cols() != 3) throw InputError("F must be #F x 3, got " + std::to_string(F.cols()) + " columns");
  if (patch.rows() != F.rows())
    throw InputError("patch has " + std::to_string(patch.rows()) + " entries for " + std::to_string(F.rows()) + " triangles");
  for (int f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      if (F(f, k) < 0 || F(f, k) >= V.rows())
        throw InputError("triangle " + std::to_string(f) + " names vertex " + std::to_string(F(f, k)) + ", but there are " +
                         std::to_string(V.rows()) + " vertices");
  return mesh::SurfaceMesh{V, F, patch};
}

/// A validated Mesh (region 0 when absent); GeometryError names the first bad cell.
inline mesh::Mesh make_mesh(const Eigen::MatrixXd& V, const CellArray& cells, const Eigen::VectorXi& types,
                            const std::optional<Eigen::VectorXi>& region) {
  mesh::Mesh m;
  m.V = V;
  m.cells = cells;
  m.types = types;
  m.region = region ? *region : Eigen::VectorXi::Zero(cells.rows());
  mesh::validate(m);
  return m;
}

inline py::tuple surface_tuple(const mesh::SurfaceMesh& s) { return py::make_tuple(s.V, s.F, s.patch); }
inline py::tuple mesh_tuple(const mesh::Mesh& m) { return py::make_tuple(m.V, m.cells, m.types, m.region); }

inline py::dict type_dict(const quality::TypeStats& s) {
  py::dict d;
  d["count"] = s.count;
  d["sj_min"] = s.sj_min;
  d["sj_mean"] = s.sj_mean;
  d["inverted"] = s.inverted;
  d["edge_ratio_min"] = s.edge_ratio_min;
  d["edge_ratio_max"] = s.edge_ratio_max;
  d["volume"] = s.volume;
  d["histogram"] = std::vector<int>(s.histogram.begin(), s.histogram.end());
  return d;
}

inline py::dict report_dict(const quality::QualityReport& r) {
  py::dict d;
  d["hex"] = type_dict(r.hex);
  d["prism"] = type_dict(r.prism);
  d["tet"] = type_dict(r.tet);
  d["total_volume"] = r.total_volume;
  return d;
}

/// A frame given from Python: InputError unless it is a rotation (orthonormal to 1e-9, determinant +1).
inline Eigen::Matrix3d checked_rotation(const Eigen::Matrix3d& R) {
  if (!R.allFinite() || (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() > 1e-9 || R.determinant() <= 0)
    throw InputError("frame must be a 3 x 3 rotation matrix (orthonormal, determinant +1)");
  return R;
}

inline py::dict frame_dict(const segmentation::CubeFrame& f) {
  py::dict d;
  d["rotation"] = Eigen::MatrixXd(f.rotation);
  d["fit"] = f.fit;
  d["fit_identity"] = f.fit_identity;
  d["angle"] = f.angle_degrees;
  d["axis"] = std::vector<double>{f.axis.x(), f.axis.y(), f.axis.z()};
  d["turned"] = f.turned();
  return d;
}

}  // namespace hexdom::python
