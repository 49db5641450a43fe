// Test fixtures: structured hex grids (VTK node order) for the optimiser's suites.
#pragma once

#include <Eigen/Dense>
#include <random>

#include "hexdom/mesh/mesh.h"

namespace hexdom::test {

/// Node row of grid point (i, j, l) when rows run x fastest, then y, then z: i + mx (j + my l).
inline int grid_node(int i, int j, int l, int mx, int my) { return i + mx * (j + my * l); }

/// Cells of an nx x nx x nz grid over the points V (row grid_node(i, j, l, mx, my)), cell (i, j, l)
/// after cell (i - 1, j, l), all of material 1. Hexes in VTK order; with `two_prisms`, the last cell
/// is instead two wedges (VTK order) split along its 0-2 / 4-6 diagonal plane.
inline mesh::Mesh grid_cells(const Eigen::MatrixXd& V, int nx, int nz, int mx, int my, bool two_prisms = false) {
  auto id = [&](int i, int j, int l) { return grid_node(i, j, l, mx, my); };
  mesh::MeshBuilder b;
  for (int l = 0; l < nz; ++l)
    for (int j = 0; j < nx; ++j)
      for (int i = 0; i < nx; ++i) {
        const int h[8] = {id(i, j, l), id(i + 1, j, l), id(i + 1, j + 1, l), id(i, j + 1, l),
                          id(i, j, l + 1), id(i + 1, j, l + 1), id(i + 1, j + 1, l + 1), id(i, j + 1, l + 1)};
        if (two_prisms && i == nx - 1 && j == nx - 1 && l == nz - 1) {
          const int w1[6] = {h[0], h[1], h[2], h[4], h[5], h[6]}, w2[6] = {h[0], h[2], h[3], h[4], h[6], h[7]};
          b.add(mesh::CellType::Wedge, w1, 1);
          b.add(mesh::CellType::Wedge, w2, 1);
        } else {
          b.add(mesh::CellType::Hex, h, 1);
        }
      }
  return b.finish(V);
}

/// True when node v of an n x n x n grid (rows as grid_node) lies on the grid's outer faces.
inline bool on_grid_boundary(int v, int n) {
  const int i = v % (n + 1), j = v / (n + 1) % (n + 1), l = v / ((n + 1) * (n + 1));
  return i == 0 || j == 0 || l == 0 || i == n || j == n || l == n;
}

/// n x n x n cubes of edge `edge` with a corner at the origin (see grid_cells; node (i, j, l) at
/// edge (i, j, l)). Each node off the outer faces is moved by up to `jitter` edges along each axis:
/// uniform draws of std::mt19937(seed), x then y then z, node by node in row order. The outer
/// faces stay flat, so the grid still fills the cube [0, n edge]^3.
inline mesh::Mesh jittered_cube_grid(int n, double jitter, unsigned seed, double edge = 1.0, bool two_prisms = false) {
  const int m = n + 1;
  Eigen::MatrixXd V(m * m * m, 3);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-jitter, jitter);
  for (int l = 0; l < m; ++l)
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < m; ++i) {
        const int v = grid_node(i, j, l, m, m);
        Eigen::RowVector3d p(i, j, l);
        if (jitter > 0 && !on_grid_boundary(v, n))
          for (int d = 0; d < 3; ++d) p(d) += u(rng);
        V.row(v) = edge * p;
      }
  return grid_cells(V, n, n, m, m, two_prisms);
}

}  // namespace hexdom::test
