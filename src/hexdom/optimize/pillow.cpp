#include "hexdom/optimize/pillow.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <limits>
#include <map>
#include <set>
#include <unordered_set>

#include "hexdom/common/error.h"
#include "hexdom/mesh/cell_faces.h"
#include "hexdom/mesh/edge_key.h"
#include "hexdom/quality/metrics.h"

namespace hexdom::optimize {

using mesh::CellType;
using quality::cell_points;
using quality::is_inverted;
using quality::scaled_jacobian;
using Vec = Eigen::Vector3d;

namespace {

// Each moved node's layer thickness (see pillow_faces in the header): depth x its shortest edge
// on the layer's faces, or share x the shortest edge off them, up to that shortest layer edge.
// `mask` as in pillow_faces (null: every boundary face).
std::vector<double> layer_thickness(const mesh::Mesh& m, const std::vector<mesh::BoundaryFace>& faces,
                                    const std::vector<char>* mask, const std::vector<int>& copy,
                                    const std::vector<double>& shortest, double depth, double share) {
  const int nn = m.num_nodes();
  std::vector<double> thickness(nn, 0.0);
  std::vector<double> under(nn, std::numeric_limits<double>::max());
  if (share > 0) {
    std::unordered_set<mesh::EdgeKey> on_layer;
    for (size_t k = 0; k < faces.size(); ++k)
      if (!mask || (*mask)[k])
        for (int i = 0; i < faces[k].n; ++i) on_layer.insert(mesh::undirected_edge(faces[k].v[i], faces[k].v[(i + 1) % faces[k].n]));
    for (int c = 0; c < m.num_cells(); ++c) {
      const auto [edges, ne] = mesh::cell_edges(m.type(c));
      for (int e = 0; e < ne; ++e) {
        const int a = m.cells(c, edges[e][0]), b = m.cells(c, edges[e][1]);
        if ((copy[a] < 0 && copy[b] < 0) || on_layer.count(mesh::undirected_edge(a, b))) continue;
        const double l = (m.V.row(a) - m.V.row(b)).norm();
        under[a] = std::min(under[a], l);
        under[b] = std::min(under[b], l);
      }
    }
  }
  for (int v = 0; v < nn; ++v) {
    if (copy[v] < 0) continue;
    // A node whose every edge lies on the layer (a corner of a cell with three faces on it): the
    // cell under it is as high as its edges are long.
    const double height = under[v] < std::numeric_limits<double>::max() ? under[v] : shortest[v];
    thickness[v] = std::max(depth * shortest[v], std::min(shortest[v], share * height));
  }
  return thickness;
}

}  // namespace

mesh::Mesh pillow_faces(const mesh::Mesh& m, double depth, const std::vector<char>* mask, std::vector<int>* old_to_new,
                        const std::vector<double>* node_scale, double share) {
  const auto faces = mesh::boundary_faces(m);
  if (mask && mask->size() != faces.size())
    throw GeometryError("pillow: " + std::to_string(mask->size()) + " face flags for " + std::to_string(faces.size()) +
                        " boundary faces");
  auto selected = [&](size_t f) { return !mask || (*mask)[f]; };
  const int nn = m.num_nodes();
  std::vector<int> copy(nn, -1);
  std::vector<double> shortest(nn, std::numeric_limits<double>::max());
  int next = nn;
  for (size_t k = 0; k < faces.size(); ++k) {
    if (!selected(k)) continue;
    const auto& f = faces[k];
    for (int i = 0; i < f.n; ++i) {
      const int v = f.v[i], w = f.v[(i + 1) % f.n];
      if (copy[v] < 0) copy[v] = next++;
      const double l = (m.V.row(v) - m.V.row(w)).norm();
      shortest[v] = std::min(shortest[v], l);
      shortest[w] = std::min(shortest[w], l);
    }
  }
  const std::vector<double> thickness = layer_thickness(m, faces, mask, copy, shortest, depth, share);
  Eigen::MatrixXd V(next, 3);
  V.topRows(nn) = m.V;
  for (int v = 0; v < nn; ++v)
    if (copy[v] >= 0) V.row(copy[v]) = m.V.row(v);
  mesh::MeshBuilder b;
  b.cells.reserve(m.num_cells() + faces.size());
  for (int c = 0; c < m.num_cells(); ++c) {
    b.cells.push_back({});
    for (int i = 0; i < 8; ++i) b.cells.back()[i] = m.cells(c, i);
    b.types.push_back(m.types(c));
    b.region.push_back(m.region(c));
  }
  std::vector<int> layer_face;  // the boundary face under each new cell
  for (size_t k = 0; k < faces.size(); ++k) {
    if (!selected(k)) continue;
    const auto& f = faces[k];
    layer_face.push_back(static_cast<int>(k));
    if (f.n == 4) {
      int h[8] = {f.v[0], f.v[1], f.v[2], f.v[3], copy[f.v[0]], copy[f.v[1]], copy[f.v[2]], copy[f.v[3]]};
      b.add(CellType::Hex, h, m.region(f.cell));
    } else {
      int w[6] = {copy[f.v[0]], copy[f.v[1]], copy[f.v[2]], f.v[0], f.v[1], f.v[2]};
      b.add(CellType::Wedge, w, m.region(f.cell));
    }
  }
  mesh::Mesh out = b.finish(V);
  // Move every old boundary node inward at once; then, where a cell that was valid in the input (or
  // is a new layer cell) comes out inverted, halve the depth of its moved nodes and try again.
  std::vector<double> scale(nn, 1.0);
  if (node_scale && static_cast<int>(node_scale->size()) == nn) scale = *node_scale;
  std::vector<Vec> dir(nn, Vec::Zero());
  // Inward direction: one that makes a positive angle with every corner normal of the node's
  // layer faces (else a thin layer cell on a warped face inverts at that corner, however thin):
  // start from the mean corner normal and lean toward the worst one until all agree.
  {
    std::vector<std::vector<Vec>> corner_normals(nn), left_normals(nn);
    std::vector<Vec> left_ahead(nn, Vec::Zero());  // sum of (centroid - node) over faces left out
    for (size_t k = 0; k < faces.size(); ++k) {
      const auto& f = faces[k];
      Vec c = Vec::Zero();
      for (int i = 0; i < f.n; ++i) c += m.V.row(f.v[i]).transpose();
      c /= f.n;
      for (int i = 0; i < f.n; ++i) {
        const Vec p = m.V.row(f.v[i]).transpose();
        const Vec a = m.V.row(f.v[(i + 1) % f.n]).transpose() - p, e = m.V.row(f.v[(i + f.n - 1) % f.n]).transpose() - p;
        const Vec cn = a.cross(e);
        if (selected(k)) {
          if (cn.norm() > 0) corner_normals[f.v[i]].push_back(-cn.normalized());  // inward
        } else if (copy[f.v[i]] >= 0) {
          if (cn.norm() > 0) left_normals[f.v[i]].push_back(-cn.normalized());
          left_ahead[f.v[i]] += c - p;
        }
      }
    }
    for (int v = 0; v < nn; ++v) {
      if (copy[v] < 0 || corner_normals[v].empty()) continue;
      Vec d = Vec::Zero();
      for (const Vec& q : corner_normals[v]) d += q;
      if (!(d.norm() > 0)) d = corner_normals[v][0];
      d.normalize();
      for (int it = 0; it < 30; ++it) {
        const Vec* worst = nullptr;
        double w = 2;
        for (const Vec& q : corner_normals[v])
          if (d.dot(q) < w) { w = d.dot(q); worst = &q; }
        if (w > 0.3 || !worst) break;
        d = (d + 0.5 * *worst).normalized();
      }
      if (!left_normals[v].empty()) {
        // On the edge of the layer: along the faces left out. Their normals span one direction
        // (one smooth face: move in its tangent plane), two (two faces meeting at an angle: move
        // along the line where they meet) or three (a corner: no move keeps the node on them).
        Eigen::Matrix3d N = Eigen::Matrix3d::Zero();
        for (const Vec& q : left_normals[v]) N += q * q.transpose();
        const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(N);  // ascending eigenvalues
        const Eigen::Vector3d lam = es.eigenvalues();
        const int normals = (lam(2) > 0) + (lam(1) > 0.1 * lam(2)) + (lam(0) > 0.1 * lam(2));
        Vec t = Vec::Zero();
        if (normals == 1) t = d - es.eigenvectors().col(2) * es.eigenvectors().col(2).dot(d);
        else if (normals == 2) t = es.eigenvectors().col(0) * es.eigenvectors().col(0).dot(d);
        const Vec ahead = left_ahead[v].normalized();
        if (!(t.norm() > 0.05) || !(t.normalized().dot(ahead) > 0.1))
          throw GeometryError("pillow: node " + std::to_string(v + 1) +
                              " lies where the layer ends, and no move inward keeps it on the faces left out" +
                              (normals >= 3 ? " (a corner of them)" : ""));
        d = t.normalized();
      }
      dir[v] = d;
    }
  }
  std::vector<char> was_valid(out.num_cells(), 1);
  for (int c = 0; c < m.num_cells(); ++c) was_valid[c] = !is_inverted(scaled_jacobian(m.type(c), cell_points(m, c)));
  // A layer cell on the face of an inverted cell inherits its orientation: no depth mends it.
  for (size_t k = 0; k < layer_face.size(); ++k) was_valid[m.num_cells() + k] = was_valid[faces[layer_face[k]].cell];
  for (int attempt = 0; attempt < 8; ++attempt) {
    for (int v = 0; v < nn; ++v)
      if (copy[v] >= 0) out.V.row(v) = (m.V.row(v).transpose() + scale[v] * thickness[v] * dir[v]).transpose();
    bool all_ok = true;
    std::vector<char> shrink(nn, 0);
    for (int c = 0; c < out.num_cells(); ++c) {
      if (!was_valid[c] || !is_inverted(scaled_jacobian(out.type(c), cell_points(out, c)))) continue;
      for (int i = 0; i < mesh::node_count(out.type(c)); ++i) {
        const int v = out.cells(c, i);
        if (v < nn && copy[v] >= 0) { shrink[v] = 1; all_ok = false; }
      }
    }
    if (all_ok) break;
    for (int v = 0; v < nn; ++v)
      if (shrink[v]) scale[v] *= 0.5;
  }
  if (old_to_new) *old_to_new = copy;
  return out;
}

mesh::Mesh pillow(const mesh::Mesh& m, double depth, std::vector<int>* old_to_new) {
  return pillow_faces(m, depth, nullptr, old_to_new);
}

mesh::Mesh pillow(const mesh::Mesh& m, double depth, const std::vector<char>& faces, std::vector<int>* old_to_new) {
  return pillow_faces(m, depth, &faces, old_to_new);
}

std::vector<char> smooth_layer_faces(const mesh::Mesh& m, const NodeKinds& t) {
  std::map<int, std::vector<int>> cell_faces;
  for (int f = 0; f < static_cast<int>(t.faces.size()); ++f) cell_faces[t.faces[f].cell].push_back(f);
  std::set<int> regions;
  for (const auto& [c, fs] : cell_faces)
    for (size_t i = 0; i < fs.size(); ++i)
      for (size_t j = i + 1; j < fs.size(); ++j) {
        const auto &a = t.faces[fs[i]], &b = t.faces[fs[j]];
        if (t.region[fs[i]] != t.region[fs[j]]) continue;
        int shared = 0;
        for (int x = 0; x < a.n; ++x)
          for (int y = 0; y < b.n; ++y) shared += a.v[x] == b.v[y];
        if (shared >= 2) regions.insert(t.region[fs[i]]);
      }
  if (regions.empty()) return {};
  // The layer cannot end at a reflex edge (its side faces would lie inside the part): it goes on
  // across it, over the next region too.
  auto centroid = [&](int f) {
    Vec c = Vec::Zero();
    for (int i = 0; i < t.faces[f].n; ++i) c += m.V.row(t.faces[f].v[i]).transpose();
    return Vec(c / t.faces[f].n);
  };
  for (bool grew = true; grew;) {
    grew = false;
    for (const auto& [f, g] : t.across_sharp) {
      const bool in_f = regions.count(t.region[f]) > 0, in_g = regions.count(t.region[g]) > 0;
      if (in_f == in_g) continue;
      const int a = in_f ? f : g, b = in_f ? g : f;  // a in the layer, b not
      if ((centroid(b) - centroid(a)).dot(mesh::face_area_vector(m, t.faces[a])) > 0) {  // b in front of a: reflex
        regions.insert(t.region[b]);
        grew = true;
      }
    }
  }
  std::vector<char> mask(t.faces.size(), 0);
  for (size_t f = 0; f < mask.size(); ++f) mask[f] = regions.count(t.region[f]) > 0;
  if (std::all_of(mask.begin(), mask.end(), [](char x) { return x != 0; })) return {};  // the layer everywhere
  return mask;
}

}  // namespace hexdom::optimize
