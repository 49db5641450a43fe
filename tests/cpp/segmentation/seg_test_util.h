// Surfaces built in the segmentation tests: unions of unit voxels (polycube shapes whose faces
// carry their axis label) and extruded convex polygons (prisms whose sides are CAD faces).
#pragma once

#include <array>
#include <cmath>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "hexdom/mesh/mesh.h"
#include "test_common.h"

namespace hexdom::test {

/// Boundary of a union of unit voxels, each voxel face split into m x m squares of two triangles,
/// counter-clockwise from outside; patch = axis label 1..6 (+X, -X, +Y, -Y, +Z, -Z) of the face.
/// `scale` stretches the coordinates.
inline mesh::SurfaceMesh voxel_surface(const std::vector<std::array<int, 3>>& voxels, int m = 2,
                                       Eigen::Vector3d scale = Eigen::Vector3d::Ones()) {
  std::set<std::array<int, 3>> occupied(voxels.begin(), voxels.end());
  std::map<std::array<int, 3>, int> index;
  std::vector<Eigen::Vector3d> V;
  std::vector<std::array<int, 3>> F;
  std::vector<int> patch;
  auto vertex = [&](std::array<int, 3> g) {  // g on the fine grid (voxel units x m)
    auto [it, fresh] = index.try_emplace(g, static_cast<int>(V.size()));
    if (fresh) V.emplace_back(scale(0) * g[0] / double(m), scale(1) * g[1] / double(m), scale(2) * g[2] / double(m));
    return it->second;
  };
  for (const auto& c : voxels)
    for (int axis = 0; axis < 3; ++axis)
      for (int sign : {1, -1}) {
        std::array<int, 3> nb = c;
        nb[axis] += sign;
        if (occupied.count(nb)) continue;
        const int u = (axis + 1) % 3, w = (axis + 2) % 3;  // (u, w, axis) right-handed
        for (int i = 0; i < m; ++i)
          for (int j = 0; j < m; ++j) {
            std::array<int, 3> g[4];
            for (int q = 0; q < 4; ++q) {
              g[q][axis] = m * c[axis] + (sign > 0 ? m : 0);
              g[q][u] = m * c[u] + i + (q == 1 || q == 2);
              g[q][w] = m * c[w] + j + (q >= 2);
            }
            int a = vertex(g[0]), b = vertex(g[1]), cc = vertex(g[2]), d = vertex(g[3]);
            // u x w = axis: (a, b, c) is counter-clockwise seen from +axis.
            const int label = 2 * axis + (sign > 0 ? 1 : 2);
            if (sign > 0) {
              F.push_back({a, b, cc});
              F.push_back({a, cc, d});
            } else {
              F.push_back({a, cc, b});
              F.push_back({a, d, cc});
            }
            patch.push_back(label);
            patch.push_back(label);
          }
      }
  mesh::SurfaceMesh s;
  s.V.resize(static_cast<int>(V.size()), 3);
  for (size_t i = 0; i < V.size(); ++i) s.V.row(static_cast<int>(i)) = V[i].transpose();
  s.F.resize(static_cast<int>(F.size()), 3);
  s.patch.resize(static_cast<int>(F.size()));
  for (size_t i = 0; i < F.size(); ++i) {
    s.F.row(static_cast<int>(i)) << F[i][0], F[i][1], F[i][2];
    s.patch(static_cast<int>(i)) = patch[i];
  }
  return s;
}

/// A box of nx x ny x nz voxels.
inline mesh::SurfaceMesh box_surface(int nx, int ny, int nz, int m = 2) {
  std::vector<std::array<int, 3>> v;
  for (int i = 0; i < nx; ++i)
    for (int j = 0; j < ny; ++j)
      for (int k = 0; k < nz; ++k) v.push_back({i, j, k});
  return voxel_surface(v, m);
}

/// A convex polygon (counter-clockwise in XY, as `sides` of polylines that each become one CAD face)
/// extruded over z in [0, height] with `layers` rows; caps are fans from the centroid. Patch ids:
/// side i -> i + 1, top -> #sides + 1, bottom -> #sides + 2.
inline mesh::SurfaceMesh extruded_polygon(const std::vector<std::vector<Eigen::Vector2d>>& sides, double height,
                                          int layers) {
  std::vector<Eigen::Vector2d> ring;
  std::vector<int> side_of;  // side of the segment starting at ring[i]
  for (size_t s = 0; s < sides.size(); ++s)
    for (size_t i = 0; i + 1 < sides[s].size(); ++i) {
      ring.push_back(sides[s][i]);
      side_of.push_back(static_cast<int>(s));
    }
  const int n = static_cast<int>(ring.size());
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  for (const auto& p : ring) centre += p / n;
  mesh::SurfaceMesh out;
  const int nv = n * (layers + 1) + 2;
  out.V.resize(nv, 3);
  for (int l = 0; l <= layers; ++l)
    for (int i = 0; i < n; ++i) out.V.row(l * n + i) << ring[i](0), ring[i](1), height * l / layers;
  const int bottom = n * (layers + 1), top = bottom + 1;
  out.V.row(bottom) << centre(0), centre(1), 0.0;
  out.V.row(top) << centre(0), centre(1), height;
  std::vector<std::array<int, 4>> tris;  // a, b, c, id
  const int ns = static_cast<int>(sides.size());
  for (int l = 0; l < layers; ++l)
    for (int i = 0; i < n; ++i) {
      const int j = (i + 1) % n;
      const int a = l * n + i, b = l * n + j, c = (l + 1) * n + j, d = (l + 1) * n + i;
      tris.push_back({a, b, c, side_of[i] + 1});
      tris.push_back({a, c, d, side_of[i] + 1});
    }
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    tris.push_back({layers * n + i, layers * n + j, top, ns + 1});
    tris.push_back({j, i, bottom, ns + 2});
  }
  out.F.resize(static_cast<int>(tris.size()), 3);
  out.patch.resize(static_cast<int>(tris.size()));
  for (size_t t = 0; t < tris.size(); ++t) {
    out.F.row(static_cast<int>(t)) << tris[t][0], tris[t][1], tris[t][2];
    out.patch(static_cast<int>(t)) = tris[t][3];
  }
  return out;
}

/// Points of a segment from a to b split into k pieces (k + 1 points).
inline std::vector<Eigen::Vector2d> segment_points(Eigen::Vector2d a, Eigen::Vector2d b, int k) {
  std::vector<Eigen::Vector2d> p;
  for (int i = 0; i <= k; ++i) p.push_back(a + (b - a) * (double(i) / k));
  return p;
}

/// The raw surfaces of the paper models shared under HEXDOM_DATA.
inline std::string raw_surface(const std::string& model) { return data_path("hexdom/" + model + "/" + model + ".k"); }

/// The paper's accepted patch file and initial polycube of each model.
struct PaperPatches {
  std::string model, patches, initial;
};
inline const std::vector<PaperPatches>& paper_patch_files() {
  static const std::vector<PaperPatches> p = {
      {"rockerarm", "rockerarm_indexPatch_hexdom.k", "rockerarm_initialpolycube.k"},
      {"mount1", "mount1_patch_hexdom.k", "mount1_initialpolycube_hexdom.k"},
      {"hepta", "hepta_patch_hexdom.k", "hepta_initial_polycube.k"},
      {"fertility", "fertility_indexPatch_hexdom.k", "fertility_initialpolycube.k"},
      {"ant", "ant_indexPatch_hexdom.k", "ant_initialpolycube.k"},
      {"mountwithhole", "mountwithhole_patch_hexdom.k", "mountwithhole_initialpolycube.k"},
      {"rod_demo", "rod_indexPatch_read.k", "rod_polycube_structure.k"},
  };
  return p;
}

}  // namespace hexdom::test

namespace hexdom::test {

/// Index of the vertex at (x, y, z) (exactly), or -1.
inline int vertex_at(const mesh::SurfaceMesh& s, double x, double y, double z) {
  for (int v = 0; v < s.V.rows(); ++v)
    if ((s.V.row(v) - Eigen::RowVector3d(x, y, z)).norm() < 1e-12) return v;
  return -1;
}

/// The L-shaped solid [0,2]x[0,1]x[0,1] + [0,1]x[1,2]x[0,1], faces labelled by axis.
inline mesh::SurfaceMesh l_shape(int m = 2) { return voxel_surface({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, m); }

}  // namespace hexdom::test
