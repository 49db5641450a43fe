#include "hexdom/mesh/mesh.h"

#include <algorithm>
#include <stdexcept>

#include "hexdom/common/error.h"

namespace hexdom::mesh {

int node_count(CellType type) {
  switch (type) {
    case CellType::Triangle: return 3;
    case CellType::Quad: return 4;
    case CellType::Tet: return 4;
    case CellType::Hex: return 8;
    case CellType::Wedge: return 6;
  }
  return 0;
}

bool is_volume(CellType type) {
  return type == CellType::Tet || type == CellType::Hex || type == CellType::Wedge;
}

std::string type_name(CellType type) {
  switch (type) {
    case CellType::Triangle: return "triangle";
    case CellType::Quad: return "quad";
    case CellType::Tet: return "tet";
    case CellType::Hex: return "hex";
    case CellType::Wedge: return "prism";
  }
  return "unknown";
}

CellType cell_type_from_vtk(int t) {
  switch (t) {
    case 5: case 9: case 10: case 12: case 13: return static_cast<CellType>(t);
    default: throw std::invalid_argument("unsupported VTK cell type " + std::to_string(t));
  }
}

int edge_count(CellType type) {
  switch (type) {
    case CellType::Tet: return 6;
    case CellType::Hex: return 12;
    case CellType::Wedge: return 9;
    default: return 0;
  }
}

int second_order_vtk_type(CellType type) {
  switch (type) {
    case CellType::Tet: return 24;
    case CellType::Hex: return 25;
    case CellType::Wedge: return 26;
    default: return 0;
  }
}

CellType first_order_of_vtk(int t) {
  switch (t) {
    case 24: return CellType::Tet;
    case 25: return CellType::Hex;
    case 26: return CellType::Wedge;
    default: throw std::invalid_argument("VTK cell type " + std::to_string(t) + " is not a second-order volume cell");
  }
}

int Mesh::count(CellType t) const {
  return static_cast<int>((types.array() == static_cast<int>(t)).count());
}

void validate(const Mesh& m) {
  const int n = m.num_cells();
  if (m.V.cols() != 3) throw GeometryError("node coordinates must have 3 columns, found " + std::to_string(m.V.cols()));
  if (m.types.size() != n || m.region.size() != n)
    throw GeometryError("cells (" + std::to_string(n) + "), types (" + std::to_string(m.types.size()) +
                        ") and region (" + std::to_string(m.region.size()) + ") differ in length");
  if (!m.V.allFinite()) throw GeometryError("node coordinates contain NaN or infinity");
  if (m.second_order() && m.mid.rows() != n)
    throw GeometryError("mid-edge nodes are given for " + std::to_string(m.mid.rows()) + " cells, but there are " +
                        std::to_string(n) + " cells");
  for (int c = 0; c < n; ++c) {
    CellType t;
    try {
      t = cell_type_from_vtk(m.types(c));
    } catch (const std::invalid_argument& e) {
      throw GeometryError("cell " + std::to_string(c) + ": " + e.what());
    }
    for (int i = 0; i < node_count(t); ++i)
      if (m.cells(c, i) < 0 || m.cells(c, i) >= m.num_nodes())
        throw GeometryError("cell " + std::to_string(c) + " refers to node " + std::to_string(m.cells(c, i)) +
                            ", but there are " + std::to_string(m.num_nodes()) + " nodes");
    if (!m.second_order()) continue;
    if (!is_volume(t))
      throw GeometryError("cell " + std::to_string(c) + " is a " + type_name(t) + ": a second-order mesh has volume cells only");
    for (int e = 0; e < edge_count(t); ++e)
      if (m.mid(c, e) < 0 || m.mid(c, e) >= m.num_nodes())
        throw GeometryError("cell " + std::to_string(c) + " refers to mid-edge node " + std::to_string(m.mid(c, e)) +
                            ", but there are " + std::to_string(m.num_nodes()) + " nodes");
  }
}

int cell_nodes(const Mesh& m, int c, int* nodes) {
  const CellType t = m.type(c);
  const int n = node_count(t), ne = m.second_order() ? edge_count(t) : 0;
  for (int i = 0; i < n; ++i) nodes[i] = m.cells(c, i);
  for (int e = 0; e < ne; ++e) nodes[n + e] = m.mid(c, e);
  return n + ne;
}

void require_first_order(const Mesh& m, const std::string& what) {
  if (m.second_order())
    throw InputError(what + " takes first-order cells: the mesh is second order (hex20 / wedge15 / tet10); "
                     "mesh again with order 1");
}

void MeshBuilder::add(CellType t, const int* nodes, int region_id) {
  std::array<int, 8> c;
  c.fill(-1);
  for (int i = 0; i < node_count(t); ++i) c[i] = nodes[i];
  cells.push_back(c);
  types.push_back(static_cast<int>(t));
  region.push_back(region_id);
}

Mesh MeshBuilder::finish(Eigen::MatrixXd V) const {
  Mesh m;
  m.V = std::move(V);
  const int n = static_cast<int>(cells.size());
  m.cells.resize(n, 8);
  m.types.resize(n);
  m.region.resize(n);
  for (int c = 0; c < n; ++c) {
    for (int i = 0; i < 8; ++i) m.cells(c, i) = cells[c][i];
    m.types(c) = types[c];
    m.region(c) = region[c];
  }
  return m;
}

SurfaceMesh to_surface(const Mesh& mesh) {
  SurfaceMesh s;
  s.V = mesh.V;
  int nt = 0;
  for (int c = 0; c < mesh.num_cells(); ++c) {
    CellType t = mesh.type(c);
    if (is_volume(t))
      throw GeometryError("cell " + std::to_string(c + 1) + " is a " + type_name(t) +
                          ": a surface holds only triangles and quads");
    nt += t == CellType::Quad ? 2 : 1;
  }
  s.F.resize(nt, 3);
  s.patch.resize(nt);
  int f = 0;
  for (int c = 0; c < mesh.num_cells(); ++c) {
    const auto n = mesh.cells.row(c);
    if (mesh.type(c) == CellType::Triangle) {
      s.F.row(f) << n(0), n(1), n(2);
      s.patch(f++) = mesh.region(c);
    } else {
      double d02 = (mesh.V.row(n(0)) - mesh.V.row(n(2))).squaredNorm();
      double d13 = (mesh.V.row(n(1)) - mesh.V.row(n(3))).squaredNorm();
      if (d02 <= d13) {
        s.F.row(f) << n(0), n(1), n(2);
        s.F.row(f + 1) << n(0), n(2), n(3);
      } else {
        s.F.row(f) << n(0), n(1), n(3);
        s.F.row(f + 1) << n(1), n(2), n(3);
      }
      s.patch(f) = s.patch(f + 1) = mesh.region(c);
      f += 2;
    }
  }
  return s;
}

SurfaceMesh drop_unused_vertices(const SurfaceMesh& s) {
  std::vector<int> id(s.V.rows(), -1);
  int n = 0;
  for (int f = 0; f < s.F.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      if (id[s.F(f, k)] < 0) id[s.F(f, k)] = n++;
  if (n == s.V.rows()) return s;
  SurfaceMesh out;
  out.V.resize(n, 3);
  for (int v = 0; v < s.V.rows(); ++v)
    if (id[v] >= 0) out.V.row(id[v]) = s.V.row(v);
  out.F = s.F;
  for (int f = 0; f < s.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) out.F(f, k) = id[s.F(f, k)];
  out.patch = s.patch;
  return out;
}

SurfaceMesh join_surfaces(const std::vector<const SurfaceMesh*>& surfaces) {
  Eigen::Index nv = 0, nf = 0;
  for (const SurfaceMesh* s : surfaces) nv += s->V.rows(), nf += s->F.rows();
  SurfaceMesh out;
  out.V.resize(nv, 3);
  out.F.resize(nf, 3);
  out.patch.setZero(nf);
  Eigen::Index v0 = 0, f0 = 0;
  for (const SurfaceMesh* s : surfaces) {
    out.V.middleRows(v0, s->V.rows()) = s->V;
    out.F.middleRows(f0, s->F.rows()) = s->F.array() + static_cast<int>(v0);
    if (s->patch.size() == s->F.rows()) out.patch.segment(f0, s->F.rows()) = s->patch;
    v0 += s->V.rows();
    f0 += s->F.rows();
  }
  return out;
}

Mesh from_surface(const SurfaceMesh& surface) {
  Mesh m;
  m.V = surface.V;
  const int n = static_cast<int>(surface.F.rows());
  m.cells = CellMatrix::Constant(n, 8, -1);
  m.cells.leftCols(3) = surface.F;
  m.types = Eigen::VectorXi::Constant(n, static_cast<int>(CellType::Triangle));
  m.region = surface.patch.size() == n ? surface.patch : Eigen::VectorXi::Zero(n);
  return m;
}

namespace {
// Hex edges grouped by direction (x, y, z), as node pairs in VTK order.
const int kEdges[3][4][2] = {{{0, 1}, {3, 2}, {4, 5}, {7, 6}},
                             {{0, 3}, {1, 2}, {4, 7}, {5, 6}},
                             {{0, 4}, {1, 5}, {2, 6}, {3, 7}}};
// Faces with outward orientation: x=0, x=1, y=0, y=1, z=0, z=1.
const int kFaces[6][4] = {{0, 4, 7, 3}, {1, 2, 6, 5}, {0, 1, 5, 4},
                          {3, 7, 6, 2}, {0, 3, 2, 1}, {4, 5, 6, 7}};
// Parametric position of each node.
const int kPos[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                        {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};

int node_at(int x, int y, int z) {
  for (int i = 0; i < 8; ++i)
    if (kPos[i][0] == x && kPos[i][1] == y && kPos[i][2] == z) return i;
  return -1;
}
}  // namespace

DegenerateHex classify_hex_nodes(const std::array<int, 8>& h) {
  std::array<int, 8> sorted = h;
  std::sort(sorted.begin(), sorted.end());
  int distinct = static_cast<int>(std::unique(sorted.begin(), sorted.end()) - sorted.begin());
  DegenerateHex r{CellType::Hex, h};
  if (distinct == 8) return r;
  if (distinct == 4) {
    r.type = CellType::Tet;
    int k = 0;
    for (int i = 0; i < 8; ++i) {
      bool seen = false;
      for (int j = 0; j < k; ++j) seen = seen || r.nodes[j] == h[i];
      if (!seen) r.nodes[k++] = h[i];
    }
    for (int i = 4; i < 8; ++i) r.nodes[i] = -1;
    return r;
  }
  if (distinct == 6) {
    // Collapsed edges: exactly two, same direction d, both on one face.
    int collapsed_dir = -1, ncollapsed = 0, e1 = -1, e2 = -1;
    for (int d = 0; d < 3; ++d)
      for (int e = 0; e < 4; ++e)
        if (h[kEdges[d][e][0]] == h[kEdges[d][e][1]]) {
          if (ncollapsed == 0) { collapsed_dir = d; e1 = e; } else { e2 = e; }
          if (ncollapsed > 0 && d != collapsed_dir) collapsed_dir = -2;
          ++ncollapsed;
        }
    if (ncollapsed == 2 && collapsed_dir >= 0) {
      const int d = collapsed_dir;
      const int a = kEdges[d][e1][0], b = kEdges[d][e2][0];
      // The two edges share a face iff their start nodes differ in exactly one coordinate.
      int diff = -1, ndiff = 0;
      for (int k = 0; k < 3; ++k)
        if (kPos[a][k] != kPos[b][k]) { diff = k; ++ndiff; }
      if (ndiff == 1) {
        // The triangles are the faces across which the two collapsed edges lie apart: the prism
        // is extruded along that direction t.
        const int t = diff;
        // Face t=0 (outward), repeated node removed, then partners across t.
        const int* f = kFaces[2 * t];
        int tri[3], k = 0;
        for (int i = 0; i < 4 && k < 3; ++i) {
          int prev = f[(i + 3) % 4];
          if (h[f[i]] == h[prev]) continue;
          tri[k++] = f[i];
        }
        if (k == 3) {
          r.type = CellType::Wedge;
          for (int i = 0; i < 3; ++i) {
            int p[3] = {kPos[tri[i]][0], kPos[tri[i]][1], kPos[tri[i]][2]};
            p[t] = 1;
            r.nodes[i] = h[tri[i]];
            r.nodes[i + 3] = h[node_at(p[0], p[1], p[2])];
          }
          r.nodes[6] = r.nodes[7] = -1;
          return r;
        }
      }
    }
  }
  std::string list;
  for (int i = 0; i < 8; ++i) list += (i ? " " : "") + std::to_string(h[i]);
  throw std::invalid_argument("8-node solid with nodes " + list + " has " +
                              std::to_string(distinct) +
                              " distinct nodes in a pattern that is neither a hexahedron, a "
                              "prism (two parallel collapsed edges of one face) nor a tetrahedron");
}

std::array<int, 8> to_hex_nodes(CellType t, const int* c) {
  switch (t) {
    case CellType::Hex: return {c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7]};
    case CellType::Wedge: return {c[0], c[2], c[1], c[1], c[3], c[5], c[4], c[4]};
    case CellType::Tet: return {c[0], c[1], c[2], c[3], c[3], c[3], c[3], c[3]};
    default: throw std::invalid_argument("only volume cells are written as 8-node solids");
  }
}

double enclosed_volume(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  double vol = 0;
  for (int t = 0; t < F.rows(); ++t) {
    const Eigen::Vector3d a = V.row(F(t, 0)), b = V.row(F(t, 1)), c = V.row(F(t, 2));
    vol += a.dot(b.cross(c));
  }
  return vol / 6.0;
}

}  // namespace hexdom::mesh
