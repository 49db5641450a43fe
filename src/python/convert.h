// Conversions between numpy arrays and the core's types, shared by every bind_<stage>.cpp.
// Surfaces come in as (V #V x 3, F #F x 3, patch #F); meshes as (V, cells #C x 8 -1 padded, VTK
// types, region), a second-order mesh's cells #C x 20 in VTK's quadratic order with types 25 / 26 /
// 24; quality reports go out as dicts keyed hex / prism / tet (and hex20 / wedge15 / tet10).
#pragma once

#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
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
/// Cells from Python: 8 columns (first order) or 20 (second order), -1 padded.
using CellArray = Eigen::Matrix<int, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

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
/// Cells of VTK's second-order types (25, 26, 24) make a second-order mesh; all cells must then be.
inline mesh::Mesh make_mesh(const Eigen::MatrixXd& V, const CellArray& cells, const Eigen::VectorXi& types,
                            const std::optional<Eigen::VectorXi>& region) {
  const Eigen::Index nc = cells.rows();
  if (types.size() != nc)
    throw GeometryError("cells (" + std::to_string(nc) + ") and types (" + std::to_string(types.size()) + ") differ in length");
  const bool second = nc > 0 && (types(0) == 24 || types(0) == 25 || types(0) == 26);
  const Eigen::Index width = second ? 20 : 8;
  if (nc > 0 && cells.cols() < (second ? 10 : 3))
    throw GeometryError("cells have " + std::to_string(cells.cols()) + " columns: " + std::to_string(width) + " expected");
  mesh::Mesh m;
  m.V = V;
  m.cells = mesh::CellMatrix::Constant(nc, 8, -1);
  m.types = types;
  if (second) m.mid = mesh::MidMatrix::Constant(nc, 12, -1);
  for (Eigen::Index c = 0; c < nc; ++c) {
    const bool quadratic = types(c) == 24 || types(c) == 25 || types(c) == 26;
    if (quadratic != second)
      throw GeometryError("cell " + std::to_string(c) + " is " + (quadratic ? "second" : "first") + " order, cell 0 " +
                          (second ? "second" : "first") + " order: a mesh of mixed order is not supported");
    const mesh::CellType t = quadratic ? mesh::first_order_of_vtk(types(c)) : static_cast<mesh::CellType>(types(c));
    if (quadratic) m.types(c) = static_cast<int>(t);
    const int n = quadratic ? mesh::node_count(t) : static_cast<int>(std::min<Eigen::Index>(8, cells.cols()));
    const int ne = quadratic ? mesh::edge_count(t) : 0;
    if (n + ne > cells.cols())
      throw GeometryError("cell " + std::to_string(c) + " has " + std::to_string(n + ne) + " nodes, but cells have " +
                          std::to_string(cells.cols()) + " columns");
    for (int i = 0; i < n; ++i) m.cells(c, i) = cells(c, i);
    for (int e = 0; e < ne; ++e) m.mid(c, e) = cells(c, n + e);
  }
  m.region = region ? *region : Eigen::VectorXi::Zero(nc);
  mesh::validate(m);
  return m;
}

inline py::tuple surface_tuple(const mesh::SurfaceMesh& s) { return py::make_tuple(s.V, s.F, s.patch); }
inline py::tuple mesh_tuple(const mesh::Mesh& m) {
  if (!m.second_order()) return py::make_tuple(m.V, m.cells, m.types, m.region);
  CellArray cells = CellArray::Constant(m.num_cells(), 20, -1);
  Eigen::VectorXi types(m.num_cells());
  int nodes[20];
  for (int c = 0; c < m.num_cells(); ++c) {
    const int k = mesh::cell_nodes(m, c, nodes);
    for (int i = 0; i < k; ++i) cells(c, i) = nodes[i];
    types(c) = m.vtk_type(c);
  }
  return py::make_tuple(m.V, cells, types, m.region);
}

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
  d["order"] = r.second_order ? 2 : 1;
  if (r.second_order) {
    const std::pair<const char*, const quality::SecondOrderStats*> types[] = {
        {"hex20", &r.hex20}, {"wedge15", &r.wedge15}, {"tet10", &r.tet10}};
    for (const auto& [name, s] : types) {
      py::dict t;
      t["count"] = s->count;
      t["sj_min"] = s->sj_min;
      t["inverted"] = s->inverted;
      t["volume"] = s->volume;
      d[name] = t;
    }
  }
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

/// Lists of ids per row (the CAD faces of each node, SnapResult::faces) as a #rows x k int array,
/// -1 padded (k at least 1), and back (rows of -1 only: empty lists).
inline CellArray padded_lists(const std::vector<std::vector<int>>& lists) {
  size_t k = 1;
  for (const auto& l : lists) k = std::max(k, l.size());
  CellArray out = CellArray::Constant(static_cast<Eigen::Index>(lists.size()), static_cast<Eigen::Index>(k), -1);
  for (size_t i = 0; i < lists.size(); ++i)
    for (size_t j = 0; j < lists[i].size(); ++j) out(i, j) = lists[i][j];
  return out;
}
inline std::vector<std::vector<int>> lists_of(const CellArray& a) {
  std::vector<std::vector<int>> out(a.rows());
  for (Eigen::Index i = 0; i < a.rows(); ++i) {
    for (Eigen::Index j = 0; j < a.cols(); ++j)
      if (a(i, j) >= 0) out[i].push_back(a(i, j));
    std::sort(out[i].begin(), out[i].end());
  }
  return out;
}

}  // namespace hexdom::python
