// Test surfaces for the automatic polycube: unions of unit cells (polycubes whose faces are split
// into n x n squares of two triangles), a triangulated cylinder, an extruded polygon (a wedge with a
// strip along its knife edge), and labels from normals.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>
#include <vector>

#include "hexdom/mesh/mesh.h"
#include "hexdom/segmentation/axis_labels.h"

namespace hexdom::test {

// Faces of the cells of `m` by sorted nodes -> the number of cells using them, and each face's nodes
// in its (first) cell's order. Face tables of its own (VTK order), not the core's.
inline std::map<std::vector<int>, int> cell_faces(const mesh::Mesh& m, std::map<std::vector<int>, std::vector<int>>* ordered = nullptr) {
  static const std::vector<std::vector<int>> hex = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  static const std::vector<std::vector<int>> wedge = {{0, 1, 2}, {3, 4, 5}, {0, 3, 4, 1}, {1, 4, 5, 2}, {2, 5, 3, 0}};
  static const std::vector<std::vector<int>> tet = {{0, 1, 2}, {0, 1, 3}, {1, 2, 3}, {0, 2, 3}};
  std::map<std::vector<int>, int> faces;
  for (int c = 0; c < m.num_cells(); ++c) {
    const auto& fs = m.type(c) == mesh::CellType::Hex ? hex : m.type(c) == mesh::CellType::Wedge ? wedge : tet;
    for (const auto& f : fs) {
      std::vector<int> vs;
      for (int i : f) vs.push_back(m.cells(c, i));
      std::vector<int> key = vs;
      std::sort(key.begin(), key.end());
      if (++faces[key] == 1 && ordered) (*ordered)[key] = vs;
    }
  }
  return faces;
}

/// Label 1..6 of the axis nearest to each triangle's normal.
inline Eigen::VectorXi labels_from_normals(const mesh::SurfaceMesh& s) {
  Eigen::VectorXi l(s.F.rows());
  for (int f = 0; f < s.F.rows(); ++f) {
    const Eigen::Vector3d a = s.V.row(s.F(f, 0)), b = s.V.row(s.F(f, 1)), c = s.V.row(s.F(f, 2));
    l(f) = segmentation::nearest_label((b - a).cross(c - a));
  }
  return l;
}

/// The surface of triangles F over vertices V (no labels).
inline mesh::SurfaceMesh surface_of(const std::vector<Eigen::RowVector3d>& V, const std::vector<std::array<int, 3>>& F) {
  mesh::SurfaceMesh s;
  s.V.resize(static_cast<int>(V.size()), 3);
  for (size_t i = 0; i < V.size(); ++i) s.V.row(i) = V[i];
  s.F.resize(static_cast<int>(F.size()), 3);
  for (size_t i = 0; i < F.size(); ++i) s.F.row(i) << F[i][0], F[i][1], F[i][2];
  return s;
}

/// Closed surface of the union of unit cells (lower corners `cells`), scaled by `scale`; every unit
/// face is split into n x n squares of two triangles; labels from normals.
inline mesh::SurfaceMesh cell_surface(const std::vector<std::array<int, 3>>& cells, int n, double scale = 1.0) {
  std::set<std::array<int, 3>> in(cells.begin(), cells.end());
  std::map<std::array<int, 3>, int> id;
  std::vector<Eigen::RowVector3d> V;
  std::vector<std::array<int, 3>> F;
  auto vertex = [&](const std::array<int, 3>& p) {
    auto [it, fresh] = id.emplace(p, static_cast<int>(V.size()));
    if (fresh) V.push_back(Eigen::RowVector3d(p[0], p[1], p[2]) * scale / n);
    return it->second;
  };
  for (const auto& c : cells)
    for (int a = 0; a < 3; ++a)
      for (int sg = -1; sg <= 1; sg += 2) {
        std::array<int, 3> nb = c;
        nb[a] += sg;
        if (in.count(nb)) continue;
        const int b = (a + 1) % 3, d = (a + 2) % 3;
        for (int i = 0; i < n; ++i)
          for (int j = 0; j < n; ++j) {
            std::array<int, 3> p[4];
            for (int k = 0; k < 4; ++k) {
              p[k] = {c[0] * n, c[1] * n, c[2] * n};
              p[k][a] += sg > 0 ? n : 0;
              p[k][b] += i + (k == 1 || k == 2);
              p[k][d] += j + (k >= 2);
            }
            int q[4];
            for (int k = 0; k < 4; ++k) q[k] = vertex(p[k]);
            // (b, d, a) is right-handed: counter-clockwise in (b, d) faces +a.
            if (sg > 0) { F.push_back({q[0], q[1], q[2]}); F.push_back({q[0], q[2], q[3]}); }
            else { F.push_back({q[0], q[2], q[1]}); F.push_back({q[0], q[3], q[2]}); }
          }
      }
  mesh::SurfaceMesh s = surface_of(V, F);
  s.patch = labels_from_normals(s);
  return s;
}

/// Fills the plane cap z = const inside the ring of vertices `outer` (positions in V) with `rings`
/// concentric rings scaled toward `centre` and a centre vertex; outward normal +z when `top`, -z
/// otherwise (clockwise seen from above).
inline void add_cap(std::vector<Eigen::RowVector3d>& V, std::vector<std::array<int, 3>>& F, std::vector<int> outer,
                    const Eigen::Vector2d& centre, double z, bool top, int rings) {
  const int seg = static_cast<int>(outer.size());
  std::vector<Eigen::Vector2d> ring;
  for (int k = 0; k < seg; ++k) ring.emplace_back(V[outer[k]](0), V[outer[k]](1));
  for (int q = rings - 1; q >= 0; --q) {
    std::vector<int> inner;
    if (q == 0) {
      inner.assign(seg, static_cast<int>(V.size()));
      V.push_back(Eigen::RowVector3d(centre(0), centre(1), z));
    } else {
      for (int k = 0; k < seg; ++k) {
        const Eigen::Vector2d p = centre + (ring[k] - centre) * q / rings;
        inner.push_back(static_cast<int>(V.size()));
        V.push_back(Eigen::RowVector3d(p(0), p(1), z));
      }
    }
    for (int k = 0; k < seg; ++k) {
      const int a = outer[k], b = outer[(k + 1) % seg], c = inner[(k + 1) % seg], d = inner[k];
      if (top) {
        F.push_back({a, b, c});
        if (q > 0) F.push_back({a, c, d});
      } else {
        F.push_back({a, c, b});
        if (q > 0) F.push_back({a, d, c});
      }
    }
    outer = inner;
  }
}

/// Closed cylinder of radius r and height h along z: `seg` segments around, `rows` rows along z,
/// caps as rings of `rings` quads strips around a centre vertex; labels from normals.
inline mesh::SurfaceMesh cylinder_surface(double r, double h, int seg, int rows, int rings) {
  std::vector<Eigen::RowVector3d> V;
  std::vector<std::array<int, 3>> F;
  // Side: rows + 1 circles of seg vertices.
  std::vector<std::vector<int>> circle(rows + 1);
  for (int i = 0; i <= rows; ++i)
    for (int k = 0; k < seg; ++k) {
      const double t = 2 * M_PI * k / seg;
      circle[i].push_back(static_cast<int>(V.size()));
      V.push_back(Eigen::RowVector3d(r * std::cos(t), r * std::sin(t), h * i / rows));
    }
  for (int i = 0; i < rows; ++i)
    for (int k = 0; k < seg; ++k) {
      const int a = circle[i][k], b = circle[i][(k + 1) % seg], c = circle[i + 1][(k + 1) % seg], d = circle[i + 1][k];
      F.push_back({a, b, c});
      F.push_back({a, c, d});
    }
  // Caps: concentric circles down to a centre vertex.
  add_cap(V, F, circle[0], Eigen::Vector2d::Zero(), 0.0, false, rings);
  add_cap(V, F, circle[rows], Eigen::Vector2d::Zero(), h, true, rings);
  mesh::SurfaceMesh s = surface_of(V, F);
  s.patch = labels_from_normals(s);
  return s;
}

/// Closed surface of a square bar with a round hole through it: the bar is x in [0, length],
/// |y|, |z| <= half_side, the hole of radius r runs along x. `m` segments per quarter turn, `rows`
/// rows along x, `rings` rings on each end between the circle and the square. Then the whole is turned
/// by `tilt` radians about the y axis (a hole whose axis is (cos tilt, 0, sin tilt)). Labels from normals.
inline mesh::SurfaceMesh holed_bar_surface(double half_side, double r, double length, int m, int rows, int rings,
                                           double tilt = 0) {
  const int n = 4 * m;
  std::map<std::array<int, 3>, int> id;
  std::vector<Eigen::RowVector3d> V;
  auto point = [&](int i, int k, int j) {  // row i, angle k, ring j (0: circle, rings: square)
    const double t = -M_PI / 4 + 2 * M_PI * k / n, c = std::cos(t), s = std::sin(t);
    const double sq = half_side / std::max(std::abs(c), std::abs(s)), rr = r + (sq - r) * j / rings;
    return Eigen::RowVector3d(length * i / rows, rr * c, rr * s);
  };
  auto vertex = [&](int i, int k, int j) {
    auto [it, fresh] = id.emplace(std::array<int, 3>{i, k % n, j}, static_cast<int>(V.size()));
    if (fresh) V.push_back(point(i, k % n, j));
    return it->second;
  };
  std::vector<std::array<int, 3>> F;
  // A quad a b c d as two triangles whose normal points along `out`.
  auto quad = [&](int a, int b, int c, int d, const Eigen::Vector3d& out) {
    for (const auto& t : {std::array<int, 3>{a, b, c}, std::array<int, 3>{a, c, d}}) {
      const Eigen::Vector3d p = V[t[0]], q = V[t[1]], w = V[t[2]];
      F.push_back((q - p).cross(w - p).dot(out) >= 0 ? t : std::array<int, 3>{t[0], t[2], t[1]});
    }
  };
  for (int i = 0; i < rows; ++i)
    for (int k = 0; k < n; ++k)
      for (int j : {rings, 0}) {  // the bar's sides face away from the axis, the hole's wall toward it
        const int a = vertex(i, k, j), b = vertex(i + 1, k, j), c = vertex(i + 1, k + 1, j), d = vertex(i, k + 1, j);
        Eigen::Vector3d out = 0.5 * (V[a] + V[c]).transpose();
        out(0) = 0;
        quad(a, b, c, d, j == 0 ? Eigen::Vector3d(-out) : out);
      }
  for (int i : {0, rows})
    for (int k = 0; k < n; ++k)
      for (int j = 0; j < rings; ++j)
        quad(vertex(i, k, j), vertex(i, k, j + 1), vertex(i, k + 1, j + 1), vertex(i, k + 1, j),
             Eigen::Vector3d(i == 0 ? -1 : 1, 0, 0));
  mesh::SurfaceMesh s = surface_of(V, F);
  const double c = std::cos(tilt), sn = std::sin(tilt);
  for (size_t i = 0; i < V.size(); ++i)
    s.V.row(i) << c * V[i](0) - sn * V[i](2), V[i](1), sn * V[i](0) + c * V[i](2);
  s.patch = labels_from_normals(s);
  return s;
}

/// Closed surface of the convex polygon `poly` (counter-clockwise in xy) extruded over z in
/// [0, height]: side j (poly[j] -> poly[j + 1]) split into segments of about `edge` and labelled
/// side_label[j]; caps of concentric rings toward the centroid labelled +Z (5) and -Z (6).
inline mesh::SurfaceMesh extruded_polygon(const std::vector<Eigen::Vector2d>& poly, const std::vector<int>& side_label,
                                          double height, double edge) {
  std::vector<Eigen::Vector2d> ring;
  std::vector<int> ring_label;
  for (size_t j = 0; j < poly.size(); ++j) {
    const Eigen::Vector2d a = poly[j], b = poly[(j + 1) % poly.size()];
    const int n = std::max(1, static_cast<int>(std::lround((b - a).norm() / edge)));
    for (int k = 0; k < n; ++k) {
      ring.push_back(a + (b - a) * k / n);
      ring_label.push_back(side_label[j]);
    }
  }
  const int seg = static_cast<int>(ring.size());
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  for (const auto& p : poly) centre += p / static_cast<double>(poly.size());
  double reach = 0;
  for (const auto& p : ring) reach = std::max(reach, (p - centre).norm());
  const int rows = std::max(1, static_cast<int>(std::lround(height / edge)));
  const int rings = std::max(1, static_cast<int>(std::lround(reach / edge)));
  std::vector<Eigen::RowVector3d> V;
  std::vector<std::array<int, 3>> F;
  std::vector<int> L;
  std::vector<std::vector<int>> circle(rows + 1);
  for (int i = 0; i <= rows; ++i)
    for (int k = 0; k < seg; ++k) {
      circle[i].push_back(static_cast<int>(V.size()));
      V.push_back(Eigen::RowVector3d(ring[k](0), ring[k](1), height * i / rows));
    }
  for (int i = 0; i < rows; ++i)
    for (int k = 0; k < seg; ++k) {
      const int a = circle[i][k], b = circle[i][(k + 1) % seg], c = circle[i + 1][(k + 1) % seg], d = circle[i + 1][k];
      F.push_back({a, b, c});
      F.push_back({a, c, d});
      L.push_back(ring_label[k]);
      L.push_back(ring_label[k]);
    }
  for (int top = 0; top < 2; ++top) {
    add_cap(V, F, top ? circle[rows] : circle[0], centre, top ? height : 0.0, top, rings);
    L.resize(F.size(), top ? 5 : 6);
  }
  mesh::SurfaceMesh s = surface_of(V, F);
  s.patch = Eigen::Map<const Eigen::VectorXi>(L.data(), static_cast<int>(L.size()));
  return s;
}

/// Volume enclosed by a closed, outward-oriented triangle surface (divergence theorem).
inline double enclosed_volume(const mesh::SurfaceMesh& s) {
  double v = 0;
  for (int f = 0; f < s.F.rows(); ++f) {
    const Eigen::Vector3d a = s.V.row(s.F(f, 0)), b = s.V.row(s.F(f, 1)), c = s.V.row(s.F(f, 2));
    v += a.dot(b.cross(c)) / 6.0;
  }
  return v;
}

/// Closed surface of the triangles `tris` (corners counter-clockwise seen from outside), each split
/// into n x n similar triangles (shared edges split alike, so the surface is closed); labels from
/// normals.
inline mesh::SurfaceMesh subdivided_triangles(const std::vector<std::array<Eigen::RowVector3d, 3>>& tris, int n) {
  std::map<std::array<long long, 3>, int> id;
  std::vector<Eigen::RowVector3d> V;
  std::vector<std::array<int, 3>> F;
  auto vertex = [&](const Eigen::RowVector3d& p) {
    const std::array<long long, 3> key{std::llround(p(0) * 1e9), std::llround(p(1) * 1e9), std::llround(p(2) * 1e9)};
    auto [it, fresh] = id.emplace(key, static_cast<int>(V.size()));
    if (fresh) V.push_back(p);
    return it->second;
  };
  for (const auto& t : tris) {
    auto P = [&](int i, int j) { return vertex(t[0] + (t[1] - t[0]) * i / double(n) + (t[2] - t[0]) * j / double(n)); };
    for (int i = 0; i < n; ++i)
      for (int j = 0; i + j < n; ++j) {
        F.push_back({P(i, j), P(i + 1, j), P(i, j + 1)});
        if (i + j + 1 < n) F.push_back({P(i + 1, j), P(i + 1, j + 1), P(i, j + 1)});
      }
  }
  mesh::SurfaceMesh s = surface_of(V, F);
  s.patch = labels_from_normals(s);
  return s;
}

/// A square pyramid: base [0, side]^2 at z = 0 (-Z), apex (side / 2, side / 2, height), its four
/// sides labelled +-X, +-Y by their normals; every face split into n x n triangles.
inline mesh::SurfaceMesh pyramid_surface(double side, double height, int n) {
  const Eigen::RowVector3d a(0, 0, 0), b(side, 0, 0), c(side, side, 0), d(0, side, 0), top(side / 2, side / 2, height);
  return subdivided_triangles({{a, d, c}, {a, c, b}, {a, b, top}, {b, c, top}, {c, d, top}, {d, a, top}}, n);
}

}  // namespace hexdom::test
