#include "hexdom/autopolycube/blocks/grid_structure.h"

#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <set>

#include "hexdom/optimize/compass_search.h"
#include "hexdom/quality/metrics.h"

namespace hexdom::autopolycube {

namespace {
constexpr int kCorner[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};

double block_quality(const mesh::Mesh& T, int b) {
  return quality::signed_sj(mesh::CellType::Hex, quality::cell_points(T, b));
}
}  // namespace

GridStructure grid_structure(const PolycubeGrid& grid, const std::map<std::array<int, 3>, int>& grid_vertex,
                             const Eigen::MatrixXd& V, const GridStructureOptions& opt) {
  GridStructure out;
  std::map<std::array<int, 3>, int> index;
  std::set<std::array<int, 3>> on_surface;
  for (const auto& q : grid.squares) {
    const int b = (q.axis + 1) % 3, c = (q.axis + 2) % 3;
    for (int di = 0; di < 2; ++di)
      for (int dj = 0; dj < 2; ++dj) {
        std::array<int, 3> p{};
        p[q.axis] = q.plane;
        p[b] = q.i + di;
        p[c] = q.j + dj;
        on_surface.insert(p);
      }
  }
  mesh::MeshBuilder builder;
  for (size_t k = 0; k < grid.cells.size(); ++k) {
    int nodes[8];
    for (int i = 0; i < 8; ++i) {
      const std::array<int, 3> p{grid.cells[k][0] + kCorner[i][0], grid.cells[k][1] + kCorner[i][1], grid.cells[k][2] + kCorner[i][2]};
      auto [it, fresh] = index.emplace(p, static_cast<int>(out.grid.size()));
      if (fresh) out.grid.push_back(p);
      nodes[i] = it->second;
    }
    builder.add(mesh::CellType::Hex, nodes, static_cast<int>(k) + 1);
  }
  const int n = static_cast<int>(out.grid.size());
  Eigen::MatrixXd X = Eigen::MatrixXd::Zero(n, 3);
  std::vector<char> fixed(n, 0);
  for (int v = 0; v < n; ++v) {
    if (!on_surface.count(out.grid[v])) continue;
    auto it = grid_vertex.find(out.grid[v]);
    if (it == grid_vertex.end())
      throw MeshingError("grid point (" + std::to_string(out.grid[v][0]) + ", " + std::to_string(out.grid[v][1]) + ", " +
                         std::to_string(out.grid[v][2]) + ") on the polycube's surface has no surface vertex");
    X.row(v) = V.row(it->second);
    fixed[v] = 1;
    ++out.boundary_vertices;
  }
  out.interior_vertices = n - out.boundary_vertices;

  // Grid-graph Laplace equation for the interior vertices.
  std::vector<std::set<int>> nbr(n);
  for (size_t k = 0; k < grid.cells.size(); ++k) {
    static const int E[12][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6}, {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
    int nodes[8];
    for (int i = 0; i < 8; ++i)
      nodes[i] = index.at({grid.cells[k][0] + kCorner[i][0], grid.cells[k][1] + kCorner[i][1], grid.cells[k][2] + kCorner[i][2]});
    for (const auto& e : E) { nbr[nodes[e[0]]].insert(nodes[e[1]]); nbr[nodes[e[1]]].insert(nodes[e[0]]); }
  }
  std::vector<int> slot(n, -1);
  int m = 0;
  for (int v = 0; v < n; ++v)
    if (!fixed[v]) slot[v] = m++;
  if (m > 0) {
    std::vector<Eigen::Triplet<double>> t;
    Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(m, 3);
    for (int v = 0; v < n; ++v) {
      if (fixed[v]) continue;
      t.emplace_back(slot[v], slot[v], static_cast<double>(nbr[v].size()));
      for (int u : nbr[v]) {
        if (fixed[u]) rhs.row(slot[v]) += X.row(u);
        else t.emplace_back(slot[v], slot[u], -1.0);
      }
    }
    Eigen::SparseMatrix<double> A(m, m);
    A.setFromTriplets(t.begin(), t.end());
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(A);
    if (solver.info() != Eigen::Success) throw MeshingError("grid structure: the Laplace system is singular");
    const Eigen::MatrixXd x = solver.solve(rhs);
    for (int v = 0; v < n; ++v)
      if (!fixed[v]) X.row(v) = x.row(slot[v]);
  }
  out.structure = builder.finish(X);
  mesh::Mesh& T = out.structure;

  // Untangling: interior vertices of poor blocks move to raise the worst block around them, with a
  // floor on their edge lengths (the scaled Jacobian does not see a block flatten to a slab).
  Eigen::VectorXd q0(T.num_cells());
  for (int b = 0; b < T.num_cells(); ++b) q0(b) = block_quality(T, b);
  out.min_quality_harmonic = T.num_cells() ? q0.minCoeff() : 1.0;
  optimize::CompassOptions co;
  co.rounds = opt.untangle_rounds;
  co.target = opt.target_quality;
  co.min_edge_share = opt.min_edge_share;
  std::vector<std::vector<int>> neighbours(n);
  for (int v = 0; v < n; ++v) neighbours[v].assign(nbr[v].begin(), nbr[v].end());
  const Eigen::VectorXd q = optimize::compass_untangle(T, fixed, neighbours, co);
  out.min_quality = T.num_cells() ? q.minCoeff() : 1.0;
  for (int b = 0; b < T.num_cells(); ++b) out.inverted += q(b) <= 0;
  if (opt.log)
    opt.log(0, "structure: " + std::to_string(T.num_cells()) + " blocks, " + std::to_string(out.boundary_vertices) +
                   " boundary and " + std::to_string(out.interior_vertices) + " interior vertices; worst block scaled Jacobian " +
                   std::to_string(out.min_quality_harmonic) + " harmonic, " + std::to_string(out.min_quality) + " untangled");
  return out;
}

}  // namespace hexdom::autopolycube
