// Isotropic remeshing of a closed triangle surface whose vertices are tied to a geometry: vertices
// inside a face move on that face, vertices on an edge curve slide along it, corners stay put. Knows
// no OCCT: the geometry comes in through RemeshGeometry (cad::tessellate gives the B-rep,
// mesh::remesh_triangles the input triangles themselves).
//
// After Botsch and Kobbelt, "A remeshing approach to multiresolution modeling" (SGP 2004): split
// edges longer than 4/3 h, collapse edges shorter than 4/5 h, flip edges, relax vertices
// tangentially, repeat; here with a graded size field h, with flips that maximise the smallest angle
// (Delaunay-like) instead of equalising valences, and a last pass aimed at the smallest angles.
#pragma once

#include <Eigen/Core>
#include <array>
#include <map>
#include <utility>
#include <vector>

#include "hexdom/common/error.h"

namespace hexdom::mesh::remesh {

enum class Kind : unsigned char { Corner, Curve, Face };

/// A mesh vertex and what it is tied to.
struct RVertex {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  Kind kind = Kind::Face;
  int owner = -1;                   ///< 0-based CAD vertex (Corner), edge (Curve) or face (Face)
  double t = 0;                     ///< curve parameter (Curve)
  Eigen::Vector2d uv = Eigen::Vector2d::Zero();  ///< surface parameters (Face)
  bool has_uv = false;              ///< uv is a usable starting guess
  double size = 0;                  ///< target edge length from the geometry at this point
  double h = 0;                     ///< graded target edge length
  bool alive = true;
};

/// What the remesher asks of the geometry.
class RemeshGeometry {
 public:
  virtual ~RemeshGeometry() = default;
  /// Puts `v` (a Face vertex) at the point of its face nearest to `p` (v.p, v.uv); false on failure.
  virtual bool project_to_face(RVertex& v, const Eigen::Vector3d& p) const = 0;
  /// Puts `v` (a Curve vertex) at the point of its edge's curve nearest to `p` (v.p, v.t).
  virtual bool project_to_curve(RVertex& v, const Eigen::Vector3d& p) const = 0;
  /// Target edge length at `v` from curvature, short edges and thin faces (not graded).
  virtual double size_at(const RVertex& v) const = 0;
  /// True when face `f` is planar.
  virtual bool is_planar(int f) const = 0;
};

struct RemeshParams {
  double max_size = 1;      ///< the target size where nothing asks for less
  double gradation = 0.3;   ///< h may grow by this much per unit of distance
  int iterations = 10;
  LogCallback log;
};

class SurfaceRemesher {
 public:
  /// `F` oriented consistently, closed and 2-manifold; `face[i]` is triangle i's CAD face.
  SurfaceRemesher(std::vector<RVertex> V, const std::vector<std::array<int, 3>>& F, std::vector<int> face,
                  const RemeshGeometry& geometry, RemeshParams params);
  /// A CAD edge discretised by a single mesh edge between two corners (so that a split of that
  /// mesh edge knows which curve to put the new vertex on).
  void set_corner_edge(int a, int b, int cad_edge);
  void run();
  /// Edges split so far. The graded size field bounds them by a small multiple of the vertices
  /// the result keeps (sizes grow away from a small feature; they do not spread along long edges).
  long splits() const { return splits_; }
  /// Compacted result: #V by 3, #F by 3, #F CAD face per triangle (0-based).
  void extract(Eigen::MatrixXd& V, Eigen::MatrixXi& F, Eigen::VectorXi& face) const;

 private:
  using Tri = std::array<int, 3>;
  bool edge_tris(int a, int b, int& t_ab, int& t_ba) const;
  int third(int t, int a, int b) const;
  bool has_edge(int a, int b) const;
  void neighbours(int v, std::vector<int>& out) const;
  int degree(int v) const { return static_cast<int>(vt_[v].size()); }
  Eigen::Vector3d normal(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) const;
  double target(int a, int b) const;
  std::vector<std::pair<int, int>> edges() const;
  int add_triangle(const Tri& t, int face);
  void remove_from(int v, int t);
  void replace_in_triangle(int t, int from, int to);

  bool split(int a, int b, int depth = 0);
  bool can_collapse(int a, int b, bool strict_length) const;
  void collapse(int a, int b);
  bool flip_improves(int a, int b, double min_gain) const;
  void flip(int a, int b);
  bool relax_vertex(int v);
  /// False for a triangle of a planar face that is degenerate or turned against the plane's normal.
  bool is_valid(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c, int face) const;

  int split_long_edges();
  int collapse_short_edges(bool strict_length);
  int flip_edges();
  void relax();
  void grade_sizes();
  int repair_small_angles(double threshold_deg);

  std::vector<RVertex> V_;
  std::vector<Tri> F_;
  std::vector<int> face_;
  std::vector<char> alive_;
  std::vector<std::vector<int>> vt_;  ///< alive triangles around each vertex
  std::map<std::pair<int, int>, int> corner_edge_;
  std::vector<Eigen::Vector3d> plane_normal_;
  mutable std::vector<int> scratch_a_, scratch_b_;  ///< neighbour lists of can_collapse  ///< per CAD face: unit normal (outward) if planar, else 0
  const RemeshGeometry& geom_;
  RemeshParams params_;
  long splits_ = 0;
};

}  // namespace hexdom::mesh::remesh
