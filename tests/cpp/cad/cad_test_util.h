// Test parts built with OpenCASCADE (box, box with a cylindrical hole, L-bracket, cylinder, sphere,
// cone, torus), written as .brep files the way a user would hand them over, and the properties
// every tessellation must have.
#pragma once

#include <BRepAlgoAPI_Cut.hxx>
#include <BRepAlgoAPI_Fuse.hxx>
#include <BRepGProp.hxx>
#include <BRepFilletAPI_MakeFillet.hxx>
#include <BRepBuilderAPI_MakePolygon.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCone.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRepPrimAPI_MakePrism.hxx>
#include <BRepPrimAPI_MakeSphere.hxx>
#include <BRepPrimAPI_MakeTorus.hxx>
#include <BRepTools.hxx>
#include <GProp_GProps.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <gp_Ax2.hxx>

#include <Eigen/Geometry>
#include <cmath>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "hexdom/cad/project.h"
#include "hexdom/cad/read_shape.h"
#include "hexdom/cad/shape.h"
#include "hexdom/cad/tessellate.h"
#include "hexdom/polycube/patch_layout.h"
#include "test_common.h"

namespace hexdom::test {

inline TopoDS_Shape make_box() { return BRepPrimAPI_MakeBox(10.0, 8.0, 6.0).Shape(); }

/// 20 x 20 x 10 box with a through hole of radius 4 along z at its centre.
inline TopoDS_Shape make_box_with_hole() {
  TopoDS_Shape box = BRepPrimAPI_MakeBox(20.0, 20.0, 10.0).Shape();
  TopoDS_Shape cyl = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(10, 10, -1), gp_Dir(0, 0, 1)), 4.0, 12.0).Shape();
  return BRepAlgoAPI_Cut(box, cyl).Shape();
}

/// L-shaped profile (legs 30 and 20, thickness 6) extruded by 15.
inline TopoDS_Shape make_l_bracket() {
  BRepBuilderAPI_MakePolygon poly;
  for (auto [x, y] : std::vector<std::pair<double, double>>{{0, 0}, {30, 0}, {30, 6}, {6, 6}, {6, 20}, {0, 20}})
    poly.Add(gp_Pnt(x, y, 0));
  poly.Close();
  TopoDS_Face face = BRepBuilderAPI_MakeFace(poly.Wire());
  return BRepPrimAPI_MakePrism(face, gp_Vec(0, 0, 15)).Shape();
}

/// 12 x 12 x 12 box with a closed 4 x 4 x 4 cavity inside: a solid with two shells.
inline TopoDS_Shape make_box_with_cavity() {
  TopoDS_Shape outer = BRepPrimAPI_MakeBox(12.0, 12.0, 12.0).Shape();
  TopoDS_Shape inner = BRepPrimAPI_MakeBox(gp_Pnt(4, 4, 4), 4.0, 4.0, 4.0).Shape();
  return BRepAlgoAPI_Cut(outer, inner).Shape();
}

/// 16 x 12 x 8 box with every edge rounded (radius 2): cylinders, spheres and tangent edges.
inline TopoDS_Shape make_filleted_box() {
  TopoDS_Shape box = BRepPrimAPI_MakeBox(16.0, 12.0, 8.0).Shape();
  BRepFilletAPI_MakeFillet fillet(box);
  for (TopExp_Explorer ex(box, TopAbs_EDGE); ex.More(); ex.Next()) fillet.Add(2.0, TopoDS::Edge(ex.Current()));
  return fillet.Shape();
}

inline TopoDS_Shape make_cylinder() { return BRepPrimAPI_MakeCylinder(5.0, 12.0).Shape(); }
inline TopoDS_Shape make_sphere() { return BRepPrimAPI_MakeSphere(5.0).Shape(); }
inline TopoDS_Shape make_cone() { return BRepPrimAPI_MakeCone(5.0, 0.0, 10.0).Shape(); }
inline TopoDS_Shape make_torus() { return BRepPrimAPI_MakeTorus(8.0, 3.0).Shape(); }

/// A wedge 40 long and 20 high whose two long faces meet at an edge of `degrees`.
inline TopoDS_Shape make_wedge(double degrees) {
  const double t = std::tan(degrees * M_PI / 180.0);
  BRepBuilderAPI_MakePolygon outline(gp_Pnt(0, 0, 0), gp_Pnt(40, 0, 0), gp_Pnt(40, 40 * t, 0), true);
  const TopoDS_Face base = BRepBuilderAPI_MakeFace(outline.Wire());
  return BRepPrimAPI_MakePrism(base, gp_Vec(0, 0, 20)).Shape();
}

/// A stadium: a box 20 x 10 x 8 with a cylinder of radius 5 at each end, tangent to its side faces.
inline TopoDS_Shape make_stadium() {
  TopoDS_Shape s = BRepPrimAPI_MakeBox(gp_Pnt(0, -5, 0), 20.0, 10.0, 8.0).Shape();
  for (double x : {0.0, 20.0})
    s = BRepAlgoAPI_Fuse(s, BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(x, 0, 0), gp_Dir(0, 0, 1)), 5.0, 8.0).Shape()).Shape();
  return s;
}

/// OpenCASCADE's volume of a solid (the reference the meshes are measured against).
inline double brep_volume(const TopoDS_Shape& s) {
  GProp_GProps g;
  BRepGProp::VolumeProperties(s, g);
  return g.Mass();
}

/// Writes `shape` as a .brep file in the test scratch folder and returns its path.
inline std::string write_part(const TopoDS_Shape& shape, const std::string& name) {
  const std::string path = temp_path(name + ".brep");
  BRepTools::Write(shape, path.c_str());
  return path;
}

inline double tri_min_angle_deg(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  auto angle = [](const Eigen::Vector3d& u, const Eigen::Vector3d& v) { return std::atan2(u.cross(v).norm(), u.dot(v)); };
  return std::min({angle(b - a, c - a), angle(a - b, c - b), angle(a - c, b - c)}) * 180.0 / 3.14159265358979323846;
}

inline double enclosed_volume(const mesh::SurfaceMesh& s) {
  double v = 0;
  for (int t = 0; t < s.F.rows(); ++t) {
    const Eigen::Vector3d a = s.V.row(s.F(t, 0)), b = s.V.row(s.F(t, 1)), c = s.V.row(s.F(t, 2));
    v += a.dot(b.cross(c));
  }
  return v / 6.0;
}

/// What the checks found, for messages and for the tests that look at one figure.
struct TessellationCheck {
  double min_angle = 180, min_angle_planar = 180;
  double mean_edge_planar = 0, max_edge = 0;
  double volume_error = 0;     ///< relative
  double worst_face_offset = 0;  ///< largest distance of a triangle centroid from its own face
  int wrong_face = 0;          ///< centroids nearer to another face than to their own (beyond tolerance)
  std::set<int> face_ids;
};

/// CAD vertices where the faces meeting there form an angle sharper than 20 degrees (summed mesh
/// angle around the vertex within one face): no triangle there can do better than the corner.
inline std::vector<Eigen::Vector3d> sharp_corners(const cad::ShapeInfo& info, const mesh::SurfaceMesh& s) {
  const double diag = info.box.diagonal().norm();
  std::vector<std::map<int, double>> sum(s.V.rows());
  for (int t = 0; t < s.F.rows(); ++t)
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d a = s.V.row(s.F(t, k)), b = s.V.row(s.F(t, (k + 1) % 3)), c = s.V.row(s.F(t, (k + 2) % 3));
      sum[s.F(t, k)][s.patch(t)] += std::atan2((b - a).cross(c - a).norm(), (b - a).dot(c - a)) * 180 / 3.14159265358979;
    }
  std::vector<Eigen::Vector3d> sharp;
  for (int v = 0; v < info.vertex_points.rows(); ++v) {
    const Eigen::Vector3d p = info.vertex_points.row(v);
    for (int i = 0; i < s.V.rows(); ++i)
      if ((Eigen::Vector3d(s.V.row(i)) - p).norm() < 1e-9 * diag)
        for (auto [f, a] : sum[i])
          if (a < 20) sharp.push_back(p);
  }
  return sharp;
}

/// Checks every property a tessellation must have (closed, 2-manifold, outward, enclosed volume
/// within `volume_tolerance` of the B-rep's, face ids right, planar triangles on their plane and
/// no smaller than 20 degrees, edges below 1.5 size) and returns the figures. `size` is the target
/// size it was made with. Triangles within one size of a CAD corner sharper than 20 degrees are
/// excused from the angle and on-the-face checks (a cusp between tangent arcs is thinner than any
/// triangle near it).
inline TessellationCheck check_tessellation(const cad::Shape& shape, const mesh::SurfaceMesh& s, double size,
                                            double volume_tolerance = 0.005) {
  TessellationCheck r;
  EXPECT_NO_THROW(polycube::check_closed_manifold(s)) << shape.source();
  const cad::ShapeInfo info = cad::shape_info(shape);
  const double vol = enclosed_volume(s);
  EXPECT_GT(vol, 0) << shape.source() << ": the triangles face inward";
  r.volume_error = std::abs(vol - info.volume) / info.volume;
  EXPECT_LT(r.volume_error, volume_tolerance) << shape.source() << ": encloses " << vol << ", B-rep " << info.volume;

  const std::vector<Eigen::Vector3d> sharp = sharp_corners(info, s);
  auto excused = [&](int t) {
    for (const auto& p : sharp)
      for (int k = 0; k < 3; ++k)
        if ((Eigen::Vector3d(s.V.row(s.F(t, k))) - p).norm() < size) return true;
    return false;
  };

  // Face ids: each centroid lies on its own face (up to the chord's sagitta), and no other face is
  // clearly nearer.
  Eigen::MatrixXd C(s.F.rows(), 3);
  for (int t = 0; t < s.F.rows(); ++t) C.row(t) = (s.V.row(s.F(t, 0)) + s.V.row(s.F(t, 1)) + s.V.row(s.F(t, 2))) / 3.0;
  const cad::Projection nearest = cad::project_to_shape(shape, C);
  const double diag = info.box.diagonal().norm();
  for (int f = 1; f <= info.faces; ++f) {
    std::vector<int> tris;
    for (int t = 0; t < s.F.rows(); ++t)
      if (s.patch(t) == f) tris.push_back(t);
    EXPECT_FALSE(tris.empty()) << shape.source() << ": Face" << f << " has no triangles";
    if (tris.empty()) continue;
    Eigen::MatrixXd P(tris.size(), 3);
    for (size_t i = 0; i < tris.size(); ++i) P.row(i) = C.row(tris[i]);
    const cad::Projection own = cad::project_to_face(shape, f, P);
    const bool planar = info.face_types[f - 1] == cad::SurfaceType::Plane;
    for (size_t i = 0; i < tris.size(); ++i) {
      if (excused(tris[i])) continue;
      r.worst_face_offset = std::max(r.worst_face_offset, own.distance(i));
      if (planar) {
        EXPECT_LT(own.distance(i), 1e-7 * diag) << shape.source() << ": triangle " << tris[i] << " off planar Face" << f;
      }
      if (own.distance(i) > nearest.distance(tris[i]) + 0.05 * size) ++r.wrong_face;
    }
  }
  EXPECT_EQ(r.wrong_face, 0) << shape.source() << ": triangles nearer to another face than to their own";
  EXPECT_LT(r.worst_face_offset, 0.1 * size) << shape.source();

  double edge_sum = 0;
  int edge_count = 0;
  for (int t = 0; t < s.F.rows(); ++t) {
    const Eigen::Vector3d a = s.V.row(s.F(t, 0)), b = s.V.row(s.F(t, 1)), c = s.V.row(s.F(t, 2));
    const double ang = tri_min_angle_deg(a, b, c);
    r.min_angle = std::min(r.min_angle, ang);
    r.face_ids.insert(s.patch(t));
    for (double l : {(b - a).norm(), (c - b).norm(), (a - c).norm()}) r.max_edge = std::max(r.max_edge, l);
    if (info.face_types[s.patch(t) - 1] != cad::SurfaceType::Plane) continue;
    if (!excused(t)) r.min_angle_planar = std::min(r.min_angle_planar, ang);
    for (double l : {(b - a).norm(), (c - b).norm(), (a - c).norm()}) edge_sum += l, ++edge_count;
  }
  r.mean_edge_planar = edge_count ? edge_sum / edge_count : 0;
  EXPECT_GE(r.min_angle_planar, 20.0) << shape.source();
  EXPECT_EQ(static_cast<int>(r.face_ids.size()), info.faces) << shape.source();
  EXPECT_LT(r.max_edge, 1.5 * size) << shape.source();
  return r;
}

}  // namespace hexdom::test
