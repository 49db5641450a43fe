// Internal to generation: the boundary curves between structure vertices and the harmonic maps of
// the surface's patches onto their block faces, and evaluating a patch at a parametric point.
#pragma once

#include <Eigen/Core>
#include <exception>
#include <map>
#include <vector>

#include "hexdom/mesh/mesh.h"
#include "hexdom/parametrization/harmonic_map.h"

namespace hexdom::generation {

using Vec3 = Eigen::Vector3d;

/// A polyline of surface vertices from one corner to another, with its cumulative arc length.
struct Curve {
  std::vector<Vec3> p;
  std::vector<double> s;  ///< s[0] = 0, s[i] = length up to p[i]
  /// The point at arc-length fraction t in [0, 1].
  Vec3 at(double t) const;
};

/// One patch mapped onto its block face's domain: the unit square (4 corners, in the face's
/// outward order at (0,0) (1,0) (1,1) (0,1)) or the unit triangle (3 corners at (0,0) (1,0) (0,1)).
struct PatchMap {
  std::vector<int> tris;  ///< the patch's surface triangles
  // The patch on its own: local vertices (in increasing surface vertex order), local triangles
  // (rows in the order of `tris`) and each local vertex's parametric position.
  std::vector<int> vertex;  ///< local -> surface vertex
  Eigen::MatrixXi F;
  Eigen::MatrixXd uv;
  std::vector<int> all;                   ///< 0 .. #tris-1, for the exhaustive search
  std::map<int, Eigen::Vector2d> domain;  ///< structure vertex -> its domain corner
  // Uniform grid over [0,1]^2 for point location.
  int g = 1;
  std::vector<std::vector<int>> cells;
};

/// Domain corner i of a face with nface (3 or 4) corners.
Eigen::Vector2d domain_corner(int nface, int i);

/// 3D point on the surface at parametric (u, v) of the patch: the triangle containing it (the one
/// with the largest smallest barycentric coordinate; the whole patch is searched when the grid's
/// candidates all miss), barycentric interpolation of its corners.
Vec3 evaluate(const PatchMap& pm, const mesh::SurfaceMesh& S, double u, double v);

/// One patch's harmonic map to solve: its local vertices and the fixed boundary positions.
struct MapJob {
  int patch = 0;
  Eigen::MatrixXd V;  ///< the patch's local vertices
  std::vector<int> bnd;
  Eigen::MatrixXd bc;
  parametrization::HarmonicMapResult result;
  std::exception_ptr error;
};

/// Solves the jobs' harmonic maps on `threads` threads, largest patches first; a job whose map
/// flips no triangle writes its uv and point-location grid into maps[job.patch] (whose F must be
/// set). The result does not depend on the number of threads. Errors are left in the jobs, for the
/// caller to report in job order.
void solve_patch_maps(std::vector<MapJob>& jobs, std::vector<PatchMap>& maps, int threads);

}  // namespace hexdom::generation
