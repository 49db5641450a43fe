// Node ids of the blocks' lattice points (shared on shared block faces, edges and vertices) and the
// cells of every block.
#include <array>
#include <utility>

#include "hexdom/common/parallel_for.h"
#include "hexdom/generation/steps.h"

namespace hexdom::generation {

using mesh::CellType;

void number_nodes(GenerationState& g) {
  const mesh::Mesh& T = g.T;
  const int n = g.n, n1 = g.n1, nb = T.num_cells();
  g.lattice.assign(nb, std::vector<int>(n1 * n1 * n1, -1));
  KeyTable shared(static_cast<size_t>(nb) * 6 * n1 * n1);  // at most 6 faces of (n+1)^2 points per block
  for (int b = 0; b < nb; ++b) {
    const CellType t = T.type(b);
    int w[8];
    for (int k = 0; k <= n; ++k)
      for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) {
          if (!in_lattice(t, n, i, j, k)) continue;
          int id;
          if (on_block_boundary(t, n, i, j, k)) {
            const int nw = weights(t, n, i, j, k, w);
            std::array<std::pair<int, int>, 8> pairs;
            int np = 0;
            for (int v = 0; v < nw; ++v)
              if (w[v]) pairs[np++] = {T.cells(b, v), w[v]};
            for (int q = 1; q < np; ++q)  // insertion sort: at most 8 entries
              for (int r = q; r > 0 && pairs[r] < pairs[r - 1]; --r) std::swap(pairs[r], pairs[r - 1]);
            Key key;
            key.fill(-1);
            for (int q = 0; q < np && q < 4; ++q) key[q] = (static_cast<long long>(pairs[q].first) << 32) | pairs[q].second;
            bool inserted = false;
            id = shared.find_or_insert(key, static_cast<int>(g.node_key.size()), inserted);
            if (inserted) { g.node_key.push_back(key); g.node_block.push_back(-1); }
          } else {
            id = static_cast<int>(g.node_key.size());
            Key none;
            none.fill(-1);
            g.node_key.push_back(none);
            g.node_block.push_back(b);
          }
          g.lattice[b][g.lidx(i, j, k)] = id;
        }
  }
}

namespace {

// Writes the cells of one block into rows [at, end) of a mesh.
struct Out {
  mesh::Mesh& m;
  long long at, end;
  void add(CellType t, const int* nodes, int region) {
    if (at >= end) throw MeshingError("generation: more cells than 8^level per block");
    int* row = m.cells.row(at).data();
    for (int i = 0; i < mesh::node_count(t); ++i) row[i] = nodes[i];
    m.types(at) = static_cast<int>(t);
    m.region(at) = region;
    ++at;
  }
};

void hex_cells(const GenerationState& g, int b, Out& out) {
  const auto& L = g.lattice[b];
  const int n = g.n;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        int c[8];
        for (int q = 0; q < 8; ++q) c[q] = L[g.lidx(i + kHexCorner[q][0], j + kHexCorner[q][1], k + kHexCorner[q][2])];
        out.add(CellType::Hex, c, b + 1);
      }
}

void wedge_cells(const GenerationState& g, int b, Out& out) {
  const auto& L = g.lattice[b];
  const int n = g.n;
  auto id = [&](int i, int j, int k) { return L[g.lidx(i, j, k)]; };
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i + j < n; ++i) {
        int up[6] = {id(i, j, k), id(i + 1, j, k), id(i, j + 1, k), id(i, j, k + 1), id(i + 1, j, k + 1), id(i, j + 1, k + 1)};
        out.add(CellType::Wedge, up, b + 1);
        if (i + j + 2 <= n) {
          int dn[6] = {id(i + 1, j, k), id(i + 1, j + 1, k), id(i, j + 1, k), id(i + 1, j, k + 1), id(i + 1, j + 1, k + 1), id(i, j + 1, k + 1)};
          out.add(CellType::Wedge, dn, b + 1);
        }
      }
}

// Regular refinement of the tet lattice: up tets, down tets, and octahedra split into four tets
// along their shortest diagonal (by the node positions X). Orientation is fixed in lattice space.
void tet_cells(const GenerationState& g, int b, Out& out) {
  const auto& L = g.lattice[b];
  const int n = g.n;
  const Eigen::MatrixXd& X = g.X;
  auto id = [&](int i, int j, int k) { return L[g.lidx(i, j, k)]; };
  auto add_tet = [&](std::array<Eigen::Vector3i, 4> q) {
    Eigen::Vector3i a = q[1] - q[0], c = q[2] - q[0], d = q[3] - q[0];
    const int det = a.dot(c.cross(d));
    if (det < 0) std::swap(q[1], q[2]);
    int ids[4];
    for (int r = 0; r < 4; ++r) ids[r] = id(q[r](0), q[r](1), q[r](2));
    out.add(CellType::Tet, ids, b + 1);
  };
  using V3 = Eigen::Vector3i;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i + j + k < n; ++i) {
        const V3 o(i, j, k);
        add_tet({o, o + V3(1, 0, 0), o + V3(0, 1, 0), o + V3(0, 0, 1)});
        if (i + j + k + 2 <= n) {
          const V3 a = o + V3(1, 0, 0), bq = o + V3(0, 1, 0), c = o + V3(0, 0, 1);
          const V3 ab = o + V3(1, 1, 0), ac = o + V3(1, 0, 1), bc = o + V3(0, 1, 1);
          // Octahedron a, b, c, ab, ac, bc: diagonals a-bc, b-ac, c-ab.
          const std::array<std::pair<V3, V3>, 3> diags = {std::make_pair(a, bc), std::make_pair(bq, ac), std::make_pair(c, ab)};
          int best = 0;
          double bl = 1e300;
          for (int d = 0; d < 3; ++d) {
            double l = (X.row(id(diags[d].first(0), diags[d].first(1), diags[d].first(2))) -
                        X.row(id(diags[d].second(0), diags[d].second(1), diags[d].second(2)))).norm();
            if (l < bl) { bl = l; best = d; }
          }
          // The four other vertices in cyclic order around the chosen diagonal.
          std::array<V3, 4> ring;
          if (best == 0) ring = {bq, ab, ac, c};
          else if (best == 1) ring = {a, ab, bc, c};
          else ring = {a, ac, bc, bq};
          for (int r = 0; r < 4; ++r) add_tet({diags[best].first, diags[best].second, ring[r], ring[(r + 1) % 4]});
          if (i + j + k + 3 <= n) add_tet({ab, ac, bc, o + V3(1, 1, 1)});
        }
      }
}

}  // namespace

void make_cells(GenerationState& g) {
  // Every block makes n^3 cells, written straight into the result: block b writes rows
  // [b n^3, (b+1) n^3), so blocks run in parallel.
  const mesh::Mesh& T = g.T;
  const int nb = T.num_cells();
  const long long N3 = g.N3;
  mesh::Mesh& result = g.result;
  const long long total_cells = static_cast<long long>(nb) * N3;
  result.cells.setConstant(total_cells, 8, -1);
  result.types.resize(total_cells);
  result.region.resize(total_cells);
  parallel_for(nb, g.nthreads, [&](int b) {
    Out out{result, b * N3, (b + 1) * N3};
    const CellType t = T.type(b);
    if (t == CellType::Hex) hex_cells(g, b, out);
    else if (t == CellType::Wedge) wedge_cells(g, b, out);
    else tet_cells(g, b, out);
    if (out.at != out.end)
      throw MeshingError("generation: block " + std::to_string(b + 1) + " made " + std::to_string(out.at - b * N3) +
                         " cells, expected " + std::to_string(N3));
  });
  result.V = std::move(g.X);
}

}  // namespace hexdom::generation
