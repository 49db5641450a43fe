#include "hexdom/generation/generate.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <atomic>
#include <exception>
#include <chrono>
#include <cstdio>
#include <functional>
#include <cmath>
#include <map>
#include <set>
#include <thread>
#include <cstdint>

#include "hexdom/parametrization/harmonic_map.h"
#include "hexdom/polycube/patch_layout.h"
#include "hexdom/quality/metrics.h"

namespace hexdom::generation {

using mesh::CellType;
using Vec3 = Eigen::Vector3d;

namespace {

// ---------------------------------------------------------------------------------------------
// Block topology: local faces (outward) and the lattice coordinates of block vertices.

struct LocalFace {
  int n;
  int v[4];
};
const LocalFace kHexFaces[6] = {{4, {0, 4, 7, 3}}, {4, {1, 2, 6, 5}}, {4, {0, 1, 5, 4}},
                                {4, {3, 7, 6, 2}}, {4, {0, 3, 2, 1}}, {4, {4, 5, 6, 7}}};
const LocalFace kWedgeFaces[5] = {{3, {0, 1, 2, -1}}, {3, {3, 5, 4, -1}}, {4, {0, 3, 4, 1}},
                                  {4, {1, 4, 5, 2}}, {4, {2, 5, 3, 0}}};
const LocalFace kTetFaces[4] = {{3, {0, 2, 1, -1}}, {3, {0, 1, 3, -1}}, {3, {1, 2, 3, -1}}, {3, {0, 3, 2, -1}}};

const int kHexCorner[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
const int kWedgeCorner[6][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {0, 1, 1}};
const int kTetCorner[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};

std::pair<const LocalFace*, int> local_faces(CellType t) {
  if (t == CellType::Hex) return {kHexFaces, 6};
  if (t == CellType::Wedge) return {kWedgeFaces, 5};
  return {kTetFaces, 4};
}
const int (*corner_table(CellType t))[3] {
  if (t == CellType::Hex) return kHexCorner;
  if (t == CellType::Wedge) return kWedgeCorner;
  return kTetCorner;
}

// Is lattice point (i,j,k) inside the block's lattice?
bool in_lattice(CellType t, int n, int i, int j, int k) {
  if (i < 0 || j < 0 || k < 0 || i > n || j > n || k > n) return false;
  if (t == CellType::Wedge) return i + j <= n;
  if (t == CellType::Tet) return i + j + k <= n;
  return true;
}
bool on_block_boundary(CellType t, int n, int i, int j, int k) {
  if (t == CellType::Hex) return i == 0 || j == 0 || k == 0 || i == n || j == n || k == n;
  if (t == CellType::Wedge) return i == 0 || j == 0 || k == 0 || k == n || i + j == n;
  return i == 0 || j == 0 || k == 0 || i + j + k == n;
}
// Integer interpolation weights of lattice point (i,j,k) on the block's local vertices, scaled so
// that they sum to n^3 for every block type: a point on a shared face or edge gets the same weights
// from every block that holds it.
int weights(CellType t, int n, int i, int j, int k, int* w) {
  if (t == CellType::Hex) {
    for (int v = 0; v < 8; ++v)
      w[v] = (kHexCorner[v][0] ? i : n - i) * (kHexCorner[v][1] ? j : n - j) * (kHexCorner[v][2] ? k : n - k);
    return 8;
  }
  if (t == CellType::Wedge) {
    int bary[3] = {n - i - j, i, j};
    for (int v = 0; v < 3; ++v) {
      w[v] = bary[v] * (n - k) * n;
      w[v + 3] = bary[v] * k * n;
    }
    return 6;
  }
  int bary[4] = {n - i - j - k, i, j, k};
  for (int v = 0; v < 4; ++v) w[v] = bary[v] * n * n;
  return 4;
}

// A lattice point on block boundaries, identified by its weights on structure vertices.
using Key = std::array<long long, 4>;

// Calls f(i) for i in [0, n) on `threads` threads (the caller's included), handing out indices in
// order; f must write only what index i owns. Rethrows the first exception by index.
template <class Fn>
void parallel_for(int n, int threads, Fn&& f) {
  threads = std::max(1, std::min(threads, n));
  if (threads == 1) {
    for (int i = 0; i < n; ++i) f(i);
    return;
  }
  std::atomic<int> next{0};
  std::vector<std::exception_ptr> errors(n);
  auto worker = [&] {
    for (int i; (i = next.fetch_add(1)) < n;) {
      try {
        f(i);
      } catch (...) {
        errors[i] = std::current_exception();
      }
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(worker);
  worker();
  for (auto& th : pool) th.join();
  for (auto& e : errors)
    if (e) std::rethrow_exception(e);
}

// Open-addressing table from keys to node ids (linear probing; sized once for the most keys a
// run can insert, so it never rehashes): a std::unordered_map allocates a node per key.
class KeyTable {
 public:
  explicit KeyTable(size_t max_keys) {
    size_t cap = 16;
    while (cap < 2 * max_keys) cap *= 2;
    keys_.resize(cap);
    ids_.assign(cap, -1);
    mask_ = cap - 1;
  }
  /// The id of `k`, inserting it with id `fresh` when absent; `inserted` says which.
  int find_or_insert(const Key& k, int fresh, bool& inserted) {
    uint64_t h = 0x9e3779b97f4a7c15ull;
    for (long long x : k) {
      h ^= static_cast<uint64_t>(x);
      h *= 0xbf58476d1ce4e5b9ull;
      h ^= h >> 31;
    }
    for (size_t i = h & mask_;; i = (i + 1) & mask_) {
      if (ids_[i] < 0) {
        keys_[i] = k;
        ids_[i] = fresh;
        inserted = true;
        return fresh;
      }
      if (keys_[i] == k) {
        inserted = false;
        return ids_[i];
      }
    }
  }

 private:
  std::vector<Key> keys_;
  std::vector<int> ids_;
  size_t mask_ = 0;
};

// Neighbour offsets of the lattices, for harmonic filling.
const int kTriNb[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {1, -1, 0}, {-1, 1, 0}};
const int kWedgeNb[8][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {1, -1, 0}, {-1, 1, 0}, {0, 0, 1}, {0, 0, -1}};
const int kTetNb[12][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1},
                           {1, -1, 0}, {-1, 1, 0}, {1, 0, -1}, {-1, 0, 1}, {0, 1, -1}, {0, -1, 1}};

// ---------------------------------------------------------------------------------------------
// Patch parameterisation and evaluation.

struct Curve {  // polyline from one corner to another, with cumulative arc length
  std::vector<Vec3> p;
  std::vector<double> s;
  Vec3 at(double t) const {
    const double target = t * s.back();
    auto it = std::upper_bound(s.begin(), s.end(), target);
    size_t i = it == s.begin() ? 0 : static_cast<size_t>(it - s.begin()) - 1;
    if (i + 1 >= p.size()) return p.back();
    const double len = s[i + 1] - s[i];
    const double a = len > 0 ? (target - s[i]) / len : 0.0;
    return (1 - a) * p[i] + a * p[i + 1];
  }
};

struct PatchMap {
  std::vector<int> tris;        // surface triangles
  // The patch on its own: local vertices (in increasing surface vertex order), local triangles
  // (rows in the order of `tris`) and each local vertex's parametric position.
  std::vector<int> vertex;      // local -> surface vertex
  Eigen::MatrixXi F;
  Eigen::MatrixXd uv;
  std::vector<int> all;         // 0 .. #tris-1, for the exhaustive search
  std::map<int, Eigen::Vector2d> domain;  // structure vertex -> its domain corner
  // Uniform grid over [0,1]^2 for point location.
  int g = 1;
  std::vector<std::vector<int>> cells;
};

void build_grid(PatchMap& pm, const mesh::SurfaceMesh& S) {
  pm.g = std::max(1, static_cast<int>(std::sqrt(static_cast<double>(pm.tris.size()) / 2.0)));
  pm.cells.assign(pm.g * pm.g, {});
  (void)S;
  pm.all.resize(pm.tris.size());
  for (size_t t = 0; t < pm.tris.size(); ++t) pm.all[t] = static_cast<int>(t);
  for (int t : pm.all) {
    double lo[2] = {1e30, 1e30}, hi[2] = {-1e30, -1e30};
    for (int k = 0; k < 3; ++k)
      for (int d = 0; d < 2; ++d) {
        lo[d] = std::min(lo[d], pm.uv(pm.F(t, k), d));
        hi[d] = std::max(hi[d], pm.uv(pm.F(t, k), d));
      }
    auto cell = [&](double x) { return std::max(0, std::min(pm.g - 1, static_cast<int>(std::floor(x * pm.g)))); };
    for (int y = cell(lo[1] - 1e-9); y <= cell(hi[1] + 1e-9); ++y)
      for (int x = cell(lo[0] - 1e-9); x <= cell(hi[0] + 1e-9); ++x) pm.cells[y * pm.g + x].push_back(t);
  }
}

// 3D point on the surface at parametric (u, v) of the patch: the triangle containing it (the one
// with the largest smallest barycentric coordinate), barycentric interpolation of its corners.
Vec3 evaluate(const PatchMap& pm, const mesh::SurfaceMesh& S, double u, double v) {
  auto cell = [&](double x) { return std::max(0, std::min(pm.g - 1, static_cast<int>(std::floor(x * pm.g)))); };
  double best = -1e30;
  Vec3 result = Vec3::Zero();
  auto try_tris = [&](const std::vector<int>& list) {
    for (int t : list) {
      const int a = pm.F(t, 0), b = pm.F(t, 1), c = pm.F(t, 2);
      const double x0 = pm.uv(a, 0), y0 = pm.uv(a, 1);
      const double d = (pm.uv(b, 0) - x0) * (pm.uv(c, 1) - y0) - (pm.uv(c, 0) - x0) * (pm.uv(b, 1) - y0);
      if (d == 0) continue;
      const double l1 = ((u - x0) * (pm.uv(c, 1) - y0) - (pm.uv(c, 0) - x0) * (v - y0)) / d;
      const double l2 = ((pm.uv(b, 0) - x0) * (v - y0) - (u - x0) * (pm.uv(b, 1) - y0)) / d;
      const double l0 = 1 - l1 - l2;
      const double m = std::min({l0, l1, l2});
      if (m > best) {
        best = m;
        double c0 = std::max(0.0, l0), c1 = std::max(0.0, l1), c2 = std::max(0.0, l2);
        const double sum = c0 + c1 + c2;
        result = (c0 * S.V.row(pm.vertex[a]) + c1 * S.V.row(pm.vertex[b]) + c2 * S.V.row(pm.vertex[c])).transpose() / sum;
      }
    }
  };
  try_tris(pm.cells[cell(v) * pm.g + cell(u)]);
  if (best < -1e-9) try_tris(pm.all);  // outside every candidate: search the whole patch
  return result;
}

Eigen::Vector2d domain_corner(int nface, int i) {
  static const double q[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  static const double t[3][2] = {{0, 0}, {1, 0}, {0, 1}};
  return nface == 4 ? Eigen::Vector2d(q[i][0], q[i][1]) : Eigen::Vector2d(t[i][0], t[i][1]);
}

std::string vertex_list(const std::vector<int>& v) {
  std::string s;
  for (size_t i = 0; i < v.size(); ++i) s += (i ? " " : "") + std::to_string(v[i] + 1);
  return s;
}

// ---------------------------------------------------------------------------------------------
// Relaxation and untangling of the nodes inside the volume.

// Scaled-Jacobian samples as Verdict defines them: at each corner the three edges in the order
// that gives a positive determinant for a valid cell (VTK node order), the hex's centre sample
// from its principal axes. The minimum over a cell's samples is its scaled Jacobian.
const int kHexEdgesAt[8][3] = {{1, 3, 4}, {2, 0, 5}, {3, 1, 6}, {0, 2, 7}, {7, 5, 0}, {4, 6, 1}, {5, 7, 2}, {6, 4, 3}};
const int kWedgeEdgesAt[6][3] = {{2, 1, 3}, {0, 2, 4}, {1, 0, 5}, {4, 5, 0}, {5, 3, 1}, {3, 4, 2}};
const int kTetEdgesAt[4][3] = {{1, 2, 3}, {2, 0, 3}, {0, 1, 3}, {0, 2, 1}};

inline double det3(const double* a, const double* b, const double* c) {
  return a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
}
inline double norm2(const double* a) { return a[0] * a[0] + a[1] * a[1] + a[2] * a[2]; }

// Per sample of a cell with corner points p: the determinant and the product of the squared
// lengths of its three edges; the sample is factor x det / sqrt(l2). Returns their number (hex 9,
// wedge 6, tet 4).
int sample_terms(CellType t, const double (*p)[3], double* det, double* l2, double& factor) {
  double e[3][3];
  if (t == CellType::Tet) {
    for (int q = 0; q < 3; ++q)
      for (int d = 0; d < 3; ++d) e[q][d] = p[q + 1][d] - p[0][d];
    const double D = det3(e[0], e[1], e[2]);
    for (int k = 0; k < 4; ++k) {
      double l = 1;
      for (int q = 0; q < 3; ++q) {
        const int o = kTetEdgesAt[k][q];
        const double f[3] = {p[o][0] - p[k][0], p[o][1] - p[k][1], p[o][2] - p[k][2]};
        l *= norm2(f);
      }
      det[k] = D;
      l2[k] = l;
    }
    factor = std::sqrt(2.0);
    return 4;
  }
  const bool hex = t == CellType::Hex;
  const int (*E)[3] = hex ? kHexEdgesAt : kWedgeEdgesAt;
  const int nk = hex ? 8 : 6;
  factor = hex ? 1.0 : 2.0 / std::sqrt(3.0);
  for (int k = 0; k < nk; ++k) {
    for (int q = 0; q < 3; ++q)
      for (int d = 0; d < 3; ++d) e[q][d] = p[E[k][q]][d] - p[k][d];
    det[k] = det3(e[0], e[1], e[2]);
    l2[k] = norm2(e[0]) * norm2(e[1]) * norm2(e[2]);
  }
  if (!hex) return 6;
  for (int d = 0; d < 3; ++d) {
    e[0][d] = p[1][d] - p[0][d] + p[2][d] - p[3][d] + p[5][d] - p[4][d] + p[6][d] - p[7][d];
    e[1][d] = p[3][d] - p[0][d] + p[2][d] - p[1][d] + p[7][d] - p[4][d] + p[6][d] - p[5][d];
    e[2][d] = p[4][d] - p[0][d] + p[5][d] - p[1][d] + p[6][d] - p[2][d] + p[7][d] - p[3][d];
  }
  det[8] = det3(e[0], e[1], e[2]);
  l2[8] = norm2(e[0]) * norm2(e[1]) * norm2(e[2]);
  return 9;
}

// Samples of a cell; a sample with a zero-length edge is -1 (Verdict: invalid).
int sj_samples(CellType t, const double (*p)[3], double* s) {
  double det[9], l2[9], factor;
  const int ns = sample_terms(t, p, det, l2, factor);
  for (int k = 0; k < ns; ++k) s[k] = l2[k] > 1e-300 ? factor * det[k] / std::sqrt(l2[k]) : -1.0;
  return ns;
}

// Whether some sample is at most `threshold` (> 0), without roots or divisions.
bool sj_at_most(CellType t, const double (*p)[3], double threshold) {
  double det[9], l2[9], factor;
  const int ns = sample_terms(t, p, det, l2, factor);
  const double r = threshold * threshold / (factor * factor);
  for (int k = 0; k < ns; ++k)
    if (!(l2[k] > 1e-300) || det[k] <= 0 || det[k] * det[k] <= r * l2[k]) return true;
  return false;
}

// Bit mask of the samples that depend on local node lv: its own corner, the corners it is an
// edge neighbour of, and the centre.
unsigned affected_mask(CellType t, int lv) {
  if (t == CellType::Tet) return 0xf;
  const bool hex = t == CellType::Hex;
  const int (*E)[3] = hex ? kHexEdgesAt : kWedgeEdgesAt;
  unsigned m = hex ? 1u << 8 : 0u;
  for (int k = 0; k < (hex ? 8 : 6); ++k)
    if (k == lv || E[k][0] == lv || E[k][1] == lv || E[k][2] == lv) m |= 1u << k;
  return m;
}

// How each node may move during relaxation: freely (inside the volume), in the parameter plane of
// its patch, along its boundary curve (both keep it on the input triangles), or not at all (corners
// of the structure).
struct NodeFreedom {
  enum Kind : signed char { Fixed = 0, Curve = 1, Patch = 2, Free = 3 };
  std::vector<signed char> kind;            ///< per node
  std::vector<std::array<double, 2>> param; ///< curve parameter t or patch (u, v) where the node was made
  std::vector<std::array<double, 2>> now;   ///< the parameters of its current position
  std::vector<const void*> where;           ///< the Curve or PatchMap of a surface node
  /// 3D position of surface node v at parameters q.
  std::function<void(int v, const double* q, double* x)> place;
  /// Clamps parameters q of surface node v into its domain.
  std::function<void(int v, double* q)> clamp;
};

// Node -> cell rows of a mesh (cells in increasing order in each row), built once for the
// relaxation and the untangling.
struct Adjacency {
  std::vector<int> start, cells;
  std::vector<signed char> count;  ///< nodes per cell
  std::vector<CellType> type;      ///< per cell
};
Adjacency node_cells(const mesh::Mesh& M) {
  Adjacency A;
  const int nn = M.num_nodes(), nc = M.num_cells();
  A.count.resize(nc);
  A.type.resize(nc);
  for (int c = 0; c < nc; ++c) {
    A.type[c] = M.type(c);
    A.count[c] = static_cast<signed char>(mesh::node_count(A.type[c]));
  }
  const int* cn = M.cells.data();
  const int stride = static_cast<int>(M.cells.cols());
  A.start.assign(nn + 1, 0);
  for (int c = 0; c < nc; ++c)
    for (int i = 0; i < A.count[c]; ++i) ++A.start[cn[c * stride + i] + 1];
  for (int v = 0; v < nn; ++v) A.start[v + 1] += A.start[v];
  A.cells.resize(A.start[nn]);
  std::vector<int> fill(A.start.begin(), A.start.end() - 1);
  for (int c = 0; c < nc; ++c)
    for (int i = 0; i < A.count[c]; ++i) A.cells[fill[cn[c * stride + i]]++] = c;
  return A;
}

// Moves nodes inside the volume (kind Free) next to cells whose scaled Jacobian (the quality
// module's, -1 for inverted cells) is at most `poor` towards the centroid of their edge
// neighbours (steps 1, 1/2, 1/4), keeping a move only when the worst of the node's cells rises;
// sweeps over those nodes in order until one moves none, at most `sweeps` times. The search for
// poor cells runs on `threads` threads. When `left` is given, it receives every cell whose
// scaled-Jacobian samples reach down to `left_threshold` (< poor) afterwards, in increasing order.
std::string relax_poor(mesh::Mesh& M, const Adjacency& adj, const std::vector<signed char>& kind, int sweeps, double poor,
                       int threads, std::vector<int>* left = nullptr, double left_threshold = 0) {
  const int nn = M.num_nodes(), nc = M.num_cells();
  auto cell_sj = [&](int c) {
    const double sj = quality::scaled_jacobian(M.type(c), quality::cell_points(M, c));
    return quality::is_inverted(sj) ? -1.0 : sj;
  };
  const int* cells = M.cells.data();  // row-major, 8 per cell
  const int stride = static_cast<int>(M.cells.cols());
  const std::vector<signed char>& cnt = adj.count;
  auto points = [&](int c, double (*p)[3]) {
    for (int i = 0; i < cnt[c]; ++i)
      for (int d = 0; d < 3; ++d) p[i][d] = M.V(cells[c * stride + i], d);
  };
  // Poor cells, in parallel over chunks of cells (each chunk writes its own flags).
  std::vector<char> is_poor(nc, 0);
  const int chunk = 4096;
  parallel_for((nc + chunk - 1) / chunk, threads, [&](int q) {
    for (int c = q * chunk; c < std::min(nc, (q + 1) * chunk); ++c) {
      double p[8][3];
      points(c, p);
      // The root-free test is a superset up to rounding; the quality module decides.
      is_poor[c] = sj_at_most(adj.type[c], p, poor + 1e-9) && cell_sj(c) <= poor;
    }
  });
  std::vector<int> poor_cells;
  std::vector<char> candidate(nn, 0);
  for (int c = 0; c < nc; ++c) {
    if (!is_poor[c]) continue;
    poor_cells.push_back(c);
    for (int i = 0; i < cnt[c]; ++i)
      if (kind[cells[c * stride + i]] == NodeFreedom::Free) candidate[cells[c * stride + i]] = 1;
  }
  // Cells that may be below left_threshold at the end: the poor ones and those around moved nodes.
  auto report_left = [&](const std::vector<int>& inc) {
    if (!left) return;
    left->clear();
    std::vector<int> all(poor_cells);
    all.insert(all.end(), inc.begin(), inc.end());
    std::sort(all.begin(), all.end());
    all.erase(std::unique(all.begin(), all.end()), all.end());
    for (int c : all) {
      double p[8][3];
      points(c, p);
      if (sj_at_most(adj.type[c], p, left_threshold + 1e-9)) left->push_back(c);
    }
  };
  std::vector<int> nodes;
  for (int v = 0; v < nn; ++v)
    if (candidate[v]) nodes.push_back(v);
  if (nodes.empty()) {
    report_left({});
    return "relaxation: no node next to a poor cell";
  }
  const std::vector<int>& start = adj.start;
  const std::vector<int>& inc = adj.cells;
  std::vector<int> around;  // cells of the candidate nodes
  for (int v : nodes) around.insert(around.end(), inc.begin() + start[v], inc.begin() + start[v + 1]);
  std::vector<double> sj(nc, 2.0);  // cached scaled Jacobian of the cells around the nodes
  for (int c : around)
    if (sj[c] == 2.0) sj[c] = cell_sj(c);
  std::vector<double> trial;
  // A node whose last try failed is skipped until a node of one of its cells moves: its try would
  // fail again (same positions, same cached values), so skipping changes nothing but the time.
  std::vector<char> dirty(candidate);
  long long moves = 0;
  int sweep = 0;
  for (; sweep < sweeps; ++sweep) {
    int moved = 0;
    for (int v : nodes) {
      if (!dirty[v]) continue;
      dirty[v] = 0;
      double before = 2;
      Vec3 avg = Vec3::Zero();
      int ne = 0;
      for (int r = start[v]; r < start[v + 1]; ++r) {
        const int c = inc[r];
        before = std::min(before, sj[c]);
        int lv = 0;
        while (M.cells(c, lv) != v) ++lv;
        const CellType t = M.type(c);
        const int (*E)[3] = t == CellType::Hex ? kHexEdgesAt : t == CellType::Wedge ? kWedgeEdgesAt : kTetEdgesAt;
        for (int q = 0; q < 3; ++q, ++ne) avg += M.V.row(M.cells(c, E[lv][q])).transpose();
      }
      if (!ne) continue;
      avg /= ne;
      const Vec3 old = M.V.row(v).transpose();
      for (double step : {1.0, 0.5, 0.25}) {
        M.V.row(v) = (old + step * (avg - old)).transpose();
        trial.clear();
        double after = 2;
        for (int r = start[v]; r < start[v + 1]; ++r) {
          trial.push_back(cell_sj(inc[r]));
          after = std::min(after, trial.back());
        }
        if (after > before + 1e-12) {
          for (int r = start[v]; r < start[v + 1]; ++r) {
            sj[inc[r]] = trial[r - start[v]];
            for (int i = 0; i < mesh::node_count(M.type(inc[r])); ++i) dirty[M.cells(inc[r], i)] = candidate[M.cells(inc[r], i)];
          }
          ++moved;
          break;
        }
        M.V.row(v) = old.transpose();
      }
    }
    moves += moved;
    if (!moved) break;
  }
  report_left(around);
  return "relaxation: " + std::to_string(nodes.size()) + " nodes next to poor cells, " + std::to_string(moves) + " moves in " +
         std::to_string(sweep) + " sweeps";
}

// Moves nodes next to poor cells (scaled Jacobian at most `poor`; surface nodes only next to cells
// at most `poor_surface`). A move is kept only when it raises the worst sample that depends on the
// node, so no cell falls below the worst it started from, and when it leaves every edge of the
// node at least a tenth of their mean length (or no shorter than its shortest was). Nodes inside the
// volume first try the centroid of their edge neighbours; nodes whose worst sample is below
// poor / 2 then descend a penalty on their samples below `poor` (surface nodes in their curve or
// patch parameters, at most `box` from where they were made), which untangles inverted cells: their
// samples are negative. Nodes of poor cells next to a moved node are visited again, up to `sweeps`
// rounds. Returns a one-line summary.
std::string untangle_nodes(mesh::Mesh& M, const Adjacency& adj, NodeFreedom& F, int sweeps, double trigger, double poor, double poor_surface,
                           double box, const std::vector<int>* candidates = nullptr, std::vector<int>* left = nullptr) {
  long long visits = 0, moves = 0, evals = 0;
  const int nn = M.num_nodes(), nc = M.num_cells();
  std::vector<double> x(3 * static_cast<size_t>(nn));
  for (int v = 0; v < nn; ++v)
    for (int d = 0; d < 3; ++d) x[3 * v + d] = M.V(v, d);
  std::vector<std::array<double, 2>>& param = F.now;
  const std::vector<signed char>& cnt = adj.count;
  const std::vector<CellType>& type = adj.type;
  auto cell_sj = [&](int c) {
    double p[8][3], s[9];
    for (int i = 0; i < cnt[c]; ++i)
      for (int d = 0; d < 3; ++d) p[i][d] = x[3 * M.cells(c, i) + d];
    const int ns = sj_samples(type[c], p, s);
    return *std::min_element(s, s + ns);
  };
  // Poor cells and the nodes they hold (only nodes of these cells and of the cells around them
  // can be visited: node -> cell rows are built for those alone).
  std::vector<double> sj(nc, 1.0);  // exact for poor cells, 1 for the others until they change
  std::vector<char> mark(nn, 0);      // 1: node of a poor cell, 2: node a visit may reach
  std::vector<int> poor_cells;
  // Only `candidates` (when given: a superset of the cells at most `trigger`, in increasing order)
  // are examined.
  for (int q = 0, qn = candidates ? static_cast<int>(candidates->size()) : nc; q < qn; ++q) {
    const int c = candidates ? (*candidates)[q] : q;
    double p[8][3];
    for (int i = 0; i < cnt[c]; ++i)
      for (int d = 0; d < 3; ++d) p[i][d] = x[3 * M.cells(c, i) + d];
    if (!sj_at_most(type[c], p, trigger)) continue;
    sj[c] = cell_sj(c);
    poor_cells.push_back(c);
    for (int i = 0; i < cnt[c]; ++i) mark[M.cells(c, i)] = 1;
  }
  if (poor_cells.empty()) {
    if (left) left->clear();
    return "untangling: no poor cell";
  }
  const std::vector<int>& start = adj.start;
  const std::vector<int>& inc = adj.cells;
  std::vector<int> ones;  // nodes of poor cells
  for (int c : poor_cells)
    for (int i = 0; i < cnt[c]; ++i) ones.push_back(M.cells(c, i));
  std::sort(ones.begin(), ones.end());
  ones.erase(std::unique(ones.begin(), ones.end()), ones.end());
  std::vector<int> reach;  // nodes a visit may reach: those of the cells around the poor cells' nodes
  for (int v : ones)
    for (int r = start[v]; r < start[v + 1]; ++r)
      for (int i = 0; i < cnt[inc[r]]; ++i) {
        const int u = M.cells(inc[r], i);
        if (!mark[u]) {
          mark[u] = 2;
          reach.push_back(u);
        }
      }
  reach.insert(reach.end(), ones.begin(), ones.end());
  std::vector<int> active;
  std::vector<char> queued(nn, 0);
  auto enqueue_cell = [&](int c, std::vector<int>& list) {
    for (int i = 0; i < cnt[c]; ++i) {
      const int v = M.cells(c, i);
      const int k = F.kind[v];
      if (!mark[v] || k == NodeFreedom::Fixed || queued[v] || (k != NodeFreedom::Free && sj[c] > poor_surface)) continue;
      queued[v] = 1;
      list.push_back(v);
    }
  };
  for (int c : poor_cells) enqueue_cell(c, active);
  const size_t first_active = active.size();

  // The visited node's cells, its local index in each and the samples that depend on it.
  struct Local { int c, lv; unsigned mask; };
  std::vector<Local> loc;
  std::vector<int> ring;  // edge neighbours of the visited node
  double shortest = 0;     // no trial may bring an edge of the visited node below this
  auto too_short = [&](const double* q) {
    for (int u : ring) {
      const double* a = &x[3 * u];
      if ((a[0] - q[0]) * (a[0] - q[0]) + (a[1] - q[1]) * (a[1] - q[1]) + (a[2] - q[2]) * (a[2] - q[2]) < shortest * shortest) return true;
    }
    return false;
  };
  // Worst affected sample (and penalty) with the visited node at q.
  auto evaluate_at = [&](const double* q, double* penalty) {
    ++evals;
    double worst = 2, pen = 0;
    for (const Local& l : loc) {
      double p[8][3], s[9];
      for (int i = 0; i < cnt[l.c]; ++i) {
        const double* src = i == l.lv ? q : &x[3 * M.cells(l.c, i)];
        p[i][0] = src[0];
        p[i][1] = src[1];
        p[i][2] = src[2];
      }
      const int ns = sj_samples(type[l.c], p, s);
      for (int k = 0; k < ns; ++k) {
        if (!(l.mask >> k & 1u)) continue;
        worst = std::min(worst, s[k]);
        if (s[k] < poor) pen += (poor - s[k]) * (poor - s[k]);
      }
    }
    if (penalty) *penalty = pen;
    return worst;
  };

  const double descent = 0.5 * poor;  // nodes whose worst sample is below this descend
  std::vector<int> next;
  for (int sweep = 0; sweep < sweeps && !active.empty(); ++sweep) {
    next.clear();
    for (int v : active) {
      ++visits;
      queued[v] = 0;
      const int kind = F.kind[v];
      const int dims = kind == NodeFreedom::Free ? 3 : kind;
      loc.clear();
      ring.clear();
      double centroid[3] = {0, 0, 0}, h = 0, lmin = 1e300;
      int ne = 0;
      double* xv = &x[3 * v];
      for (int r = start[v]; r < start[v + 1]; ++r) {
        const int c = inc[r];
        int lv = 0;
        while (M.cells(c, lv) != v) ++lv;
        loc.push_back({c, lv, affected_mask(type[c], lv)});
        const int (*E)[3] = type[c] == CellType::Hex ? kHexEdgesAt : type[c] == CellType::Wedge ? kWedgeEdgesAt : kTetEdgesAt;
        for (int q = 0; q < 3; ++q) {
          ring.push_back(M.cells(c, E[lv][q]));
          const double* u = &x[3 * ring.back()];
          for (int d = 0; d < 3; ++d) centroid[d] += u[d];
          const double l = std::sqrt((u[0] - xv[0]) * (u[0] - xv[0]) + (u[1] - xv[1]) * (u[1] - xv[1]) + (u[2] - xv[2]) * (u[2] - xv[2]));
          h += l;
          lmin = std::min(lmin, l);
          ++ne;
        }
      }
      if (!ne) continue;
      for (double& cd : centroid) cd /= ne;
      h /= ne;
      shortest = std::min(0.1 * h, lmin);
      double best = evaluate_at(xv, nullptr);
      const double before = best;
      double trial[3], tp[2];
      if (kind == NodeFreedom::Free) {
        for (double step : {1.0, 0.5, 0.25}) {
          for (int d = 0; d < 3; ++d) trial[d] = xv[d] + step * (centroid[d] - xv[d]);
          if (too_short(trial)) continue;
          const double w = evaluate_at(trial, nullptr);
          if (w > best + 1e-12) {
            best = w;
            std::copy(trial, trial + 3, xv);
            break;
          }
        }
      }
      // Descent on the penalty of poor samples, by finite differences in the node's own
      // coordinates (3D, or its curve or patch parameters), while it raises the worst sample.
      // Parameter steps are scaled by the ratio of parameter to 3D length near the node.
      double scale = 1;  // 3D length per unit parameter
      auto position = [&](const double* q, double* out) {
        if (kind == NodeFreedom::Free) std::copy(q, q + 3, out);
        else F.place(v, q, out);
      };
      double* pv = kind == NodeFreedom::Free ? xv : param[v].data();
      if (kind != NodeFreedom::Free) {
        double probe[3];
        std::copy(pv, pv + dims, tp);
        tp[0] += 1e-3;
        F.clamp(v, tp);
        position(tp, probe);
        const double dq = std::fabs(tp[0] - pv[0]);
        const double dl = std::sqrt((probe[0] - xv[0]) * (probe[0] - xv[0]) + (probe[1] - xv[1]) * (probe[1] - xv[1]) +
                                    (probe[2] - xv[2]) * (probe[2] - xv[2]));
        if (!(dq > 0) || !(dl > 0)) continue;
        scale = dl / dq;
      }
      for (int it = 0; it < (best < 0 ? 8 : 2) && best < descent; ++it) {
        double pen = 0, g[3] = {0, 0, 0}, q[3], pos[3];
        evaluate_at(xv, &pen);
        const double eps = 1e-6 * h / scale;
        for (int d = 0; d < dims; ++d) {
          std::copy(pv, pv + dims, q);
          q[d] += eps;
          position(q, pos);
          double pd = 0;
          evaluate_at(pos, &pd);
          g[d] = (pd - pen) / eps;
        }
        double gn = 0;
        for (int d = 0; d < dims; ++d) gn += g[d] * g[d];
        gn = std::sqrt(gn);
        if (!(gn > 0)) break;
        bool moved = false;
        for (double step = 0.5 * h / scale; step > 1e-3 * h / scale; step *= 0.5) {
          for (int d = 0; d < dims; ++d) q[d] = pv[d] - step * g[d] / gn;
          if (kind != NodeFreedom::Free) {
            // Within `box` of its lattice parameters, so that surface nodes keep their order.
            for (int d = 0; d < dims; ++d) q[d] = std::clamp(q[d], F.param[v][d] - box, F.param[v][d] + box);
            F.clamp(v, q);
          }
          position(q, pos);
          if (too_short(pos)) continue;
          const double w = evaluate_at(pos, nullptr);
          if (w > best + 1e-12) {
            best = w;
            std::copy(q, q + dims, pv);
            std::copy(pos, pos + 3, xv);
            moved = true;
            break;
          }
        }
        if (!moved) break;
      }
      if (best <= before + 1e-12) continue;
      ++moves;
      if (best < before + 1e-4) continue;  // too small a gain to revisit the neighbours
      for (const Local& l : loc) {
        sj[l.c] = cell_sj(l.c);
        if (sj[l.c] <= trigger) enqueue_cell(l.c, next);
      }
    }
    active.swap(next);
  }
  for (int v = 0; v < nn; ++v)
    for (int d = 0; d < 3; ++d) M.V(v, d) = x[3 * v + d];
  if (left) {  // cells still at most `trigger`: only cells of marked nodes can have changed
    std::vector<int> all;
    for (int v : reach) all.insert(all.end(), inc.begin() + start[v], inc.begin() + start[v + 1]);
    std::sort(all.begin(), all.end());
    all.erase(std::unique(all.begin(), all.end()), all.end());
    left->clear();
    for (int c : all) {
      double p[8][3];
      for (int i = 0; i < cnt[c]; ++i)
        for (int d = 0; d < 3; ++d) p[i][d] = x[3 * M.cells(c, i) + d];
      if (sj_at_most(type[c], p, trigger)) left->push_back(c);
    }
  }
  return "untangling: " + std::to_string(first_active) + " nodes next to poor cells, " + std::to_string(visits) + " visits, " +
         std::to_string(moves) + " moves, " + std::to_string(evals) + " evaluations";
}

// Slides surface nodes (kind Curve or Patch) within the surface, at most `box` in parameters from
// where they were made, to enlarge the volume the mesh's boundary encloses: each node climbs the
// volume of its boundary faces (bilinear quads: the mean of both diagonal splits, which is the
// trilinear cells' volume) by finite differences in its parameters, keeping a move only when no
// cell of the node falls below min(floor, its worst sample before). Returns a one-line summary
// with the volume gained.
std::string slide_for_volume(mesh::Mesh& M, NodeFreedom& F, int sweeps, double floor, double box) {
  const int nn = M.num_nodes(), nc = M.num_cells();
  // Boundary faces, outward, from the cells' local faces.
  std::map<std::vector<int>, std::pair<int, std::array<int, 4>>> seen;  // sorted -> (count, outward)
  for (int c = 0; c < nc; ++c) {
    auto [lf, nlf] = local_faces(M.type(c));
    for (int f = 0; f < nlf; ++f) {
      std::array<int, 4> o = {-1, -1, -1, -1};
      std::vector<int> k;
      for (int i = 0; i < lf[f].n; ++i) { o[i] = M.cells(c, lf[f].v[i]); k.push_back(o[i]); }
      std::sort(k.begin(), k.end());
      auto [it, ins] = seen.emplace(k, std::make_pair(1, o));
      if (!ins) it->second.first++;
    }
  }
  std::vector<std::array<int, 4>> bfaces;
  for (const auto& [k, v] : seen)
    if (v.first == 1) bfaces.push_back(v.second);
  auto face_volume = [&](const std::array<int, 4>& f, int v, const double* q) {
    auto P = [&](int i) -> Vec3 { return f[i] == v ? Vec3(q[0], q[1], q[2]) : Vec3(M.V.row(f[i]).transpose()); };
    auto tri = [](const Vec3& a, const Vec3& b, const Vec3& c) { return a.dot(b.cross(c)) / 6.0; };
    if (f[3] < 0) return tri(P(0), P(1), P(2));
    const Vec3 a = P(0), b = P(1), c = P(2), d = P(3);
    return 0.5 * (tri(a, b, c) + tri(a, c, d) + tri(a, b, d) + tri(b, c, d));
  };
  double total0 = 0;
  for (const auto& f : bfaces) total0 += face_volume(f, -1, nullptr);
  std::vector<std::vector<int>> node_faces(nn), node_cells(nn);
  for (size_t i = 0; i < bfaces.size(); ++i)
    for (int k = 0; k < 4 && bfaces[i][k] >= 0; ++k) node_faces[bfaces[i][k]].push_back(static_cast<int>(i));
  for (int c = 0; c < nc; ++c)
    for (int i = 0; i < mesh::node_count(M.type(c)); ++i)
      if (!node_faces[M.cells(c, i)].empty()) node_cells[M.cells(c, i)].push_back(c);
  auto worst_at = [&](int v, const double* q) {
    double w = 2;
    for (int c : node_cells[v]) {
      double p[8][3], sm[9];
      for (int i = 0; i < mesh::node_count(M.type(c)); ++i) {
        const int u = M.cells(c, i);
        for (int d = 0; d < 3; ++d) p[i][d] = u == v ? q[d] : M.V(u, d);
      }
      const int ns = sj_samples(M.type(c), p, sm);
      w = std::min(w, *std::min_element(sm, sm + ns));
    }
    return w;
  };
  std::vector<std::array<double, 2>>& param = F.now;
  long long moves = 0;
  int sweep = 0;
  for (; sweep < sweeps; ++sweep) {
    long long moved = 0;
    for (int v = 0; v < nn; ++v) {
      const int kind = F.kind[v];
      if (node_faces[v].empty() || (kind != NodeFreedom::Curve && kind != NodeFreedom::Patch)) continue;
      const int dims = kind;
      double x0[3] = {M.V(v, 0), M.V(v, 1), M.V(v, 2)}, pos[3], q[2];
      auto vol = [&](const double* x) {
        double s = 0;
        for (int f : node_faces[v]) s += face_volume(bfaces[f], v, x);
        return s;
      };
      const double v0 = vol(x0), floor_v = std::min(floor, worst_at(v, x0));
      // Parameter scale: 3D length per unit parameter near the node; h: mean edge length.
      double h = 0;
      int ne = 0;
      for (int f : node_faces[v])
        for (int k = 0; k < 4 && bfaces[f][k] >= 0; ++k)
          if (bfaces[f][k] != v) { h += (M.V.row(bfaces[f][k]) - M.V.row(v)).norm(); ++ne; }
      h /= std::max(1, ne);
      double g[2] = {0, 0};
      const double eps = 1e-4 * box;
      for (int d = 0; d < dims; ++d) {
        q[0] = param[v][0];
        q[1] = param[v][1];
        q[d] += eps;
        F.clamp(v, q);
        F.place(v, q, pos);
        const double dq = q[d] - param[v][d];
        g[d] = dq != 0 ? (vol(pos) - v0) / dq : 0;
      }
      const double gn = std::hypot(g[0], g[1]);
      if (!(gn > 0)) continue;
      for (double step = box; step > 1e-3 * box; step *= 0.5) {
        for (int d = 0; d < dims; ++d) q[d] = std::clamp(param[v][d] + step * g[d] / gn, F.param[v][d] - box, F.param[v][d] + box);
        if (dims == 1) q[1] = 0;
        F.clamp(v, q);
        F.place(v, q, pos);
        if (vol(pos) <= v0 + 1e-15 * h * h * h || worst_at(v, pos) < floor_v) continue;
        param[v] = {q[0], q[1]};
        for (int d = 0; d < 3; ++d) M.V(v, d) = pos[d];
        ++moved;
        break;
      }
    }
    moves += moved;
    if (!moved) break;
  }
  double total1 = 0;
  for (const auto& f : bfaces) total1 += face_volume(f, -1, nullptr);
  char buf[160];
  std::snprintf(buf, sizeof buf, "volume slide: %lld moves in %d sweeps, boundary volume %.6g -> %.6g (%+.3f%%)", moves, sweep,
                total0, total1, 100.0 * (total1 - total0) / std::fabs(total0));
  return buf;
}

}  // namespace

mesh::Mesh generate(const mesh::SurfaceMesh& S, const mesh::Mesh& T, const GenerateOptions& opt,
                    GenerateStats* stats_out) {
  if (opt.level < 0 || opt.level > 6)
    throw GeometryError("level " + std::to_string(opt.level) + " is outside 0..6");
  const int n = 1 << opt.level;
  const long long N3 = static_cast<long long>(n) * n * n;
  auto log = [&](const std::string& m) { if (opt.log) opt.log(0, m); };
  // Wall-clock stage times: the patch maps run on several threads, where CPU time would add up.
  auto t_last = std::chrono::steady_clock::now();
  std::string timing = "stage times (ms):";
  auto tick = [&](const char* stage) {
    const auto now = std::chrono::steady_clock::now();
    char buf[64];
    std::snprintf(buf, sizeof buf, " %s %.1f", stage, std::chrono::duration<double, std::milli>(now - t_last).count());
    timing += buf;
    t_last = now;
  };
  GenerateStats stats;
  const int nthreads = opt.threads > 0 ? opt.threads : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));

  // ---- the surface and its patches
  polycube::check_closed_manifold(S);
  const polycube::PatchLayout layout = polycube::patch_layout(S);
  const double diag = (S.V.colwise().maxCoeff() - S.V.colwise().minCoeff()).norm();
  stats.patches = static_cast<int>(layout.patches.size());
  stats.corners = static_cast<int>(layout.corners.size());
  tick("surface layout");

  // ---- the structure: blocks, snapped vertices, faces
  const int nb = T.num_cells(), nsv = T.num_nodes();
  if (nb == 0) throw GeometryError("the structure has no blocks");
  for (int b = 0; b < nb; ++b)
    if (!mesh::is_volume(T.type(b)))
      throw GeometryError("structure element " + std::to_string(b + 1) + " is a " + mesh::type_name(T.type(b)) +
                          ", not a hex, prism or tet block");
  std::vector<Vec3> P(nsv);
  std::vector<int> corner_vertex(layout.corners.size(), -1);  // surface corner -> structure vertex
  std::vector<int> vertex_corner(nsv, -1);
  {
    std::vector<char> used(nsv, 0);
    for (int b = 0; b < nb; ++b)
      for (int i = 0; i < mesh::node_count(T.type(b)); ++i) used[T.cells(b, i)] = 1;
    for (int v = 0; v < nsv; ++v) {
      P[v] = T.V.row(v).transpose();
      if (!used[v]) continue;
      double best = opt.snap_tolerance * diag;
      int bc = -1;
      for (size_t c = 0; c < layout.corners.size(); ++c) {
        double d = (S.V.row(layout.corners[c]).transpose() - P[v]).norm();
        if (d <= best) { best = d; bc = static_cast<int>(c); }
      }
      if (bc < 0) { stats.interior_vertices++; continue; }
      if (corner_vertex[bc] >= 0)
        throw GeometryError("structure vertices " + std::to_string(corner_vertex[bc] + 1) + " and " + std::to_string(v + 1) +
                            " both snap to surface corner " + std::to_string(layout.corners[bc] + 1));
      corner_vertex[bc] = v;
      vertex_corner[v] = bc;
      P[v] = S.V.row(layout.corners[bc]).transpose();
    }
  }
  for (size_t c = 0; c < layout.corners.size(); ++c)
    if (corner_vertex[c] < 0)
      throw GeometryError("surface corner at vertex " + std::to_string(layout.corners[c] + 1) + " (" +
                          std::to_string(S.V(layout.corners[c], 0)) + ", " + std::to_string(S.V(layout.corners[c], 1)) + ", " +
                          std::to_string(S.V(layout.corners[c], 2)) + ") has no structure vertex");

  // Faces of all blocks, keyed by their sorted vertices.
  std::map<std::vector<int>, std::vector<std::pair<int, int>>> faces;
  for (int b = 0; b < nb; ++b) {
    auto [lf, nlf] = local_faces(T.type(b));
    for (int f = 0; f < nlf; ++f) {
      std::vector<int> vs;
      for (int i = 0; i < lf[f].n; ++i) vs.push_back(T.cells(b, lf[f].v[i]));
      std::sort(vs.begin(), vs.end());
      faces[vs].push_back({b, f});
    }
  }
  // Patch corner sets -> patch index.
  std::map<std::vector<int>, int> patch_of_corners;
  for (size_t p = 0; p < layout.patches.size(); ++p) {
    std::vector<int> vs;
    for (int li : layout.patches[p].corners) vs.push_back(corner_vertex[layout.corner_of(layout.patches[p].loop[li])]);
    std::sort(vs.begin(), vs.end());
    patch_of_corners[vs] = static_cast<int>(p);
  }
  std::vector<PatchMap> maps(layout.patches.size());
  std::vector<int> patch_face(layout.patches.size(), -1);
  std::map<std::vector<int>, int> boundary_face_patch;  // sorted vertices -> patch
  std::map<std::pair<int, int>, Curve> curves;          // (structure vertex a, b) -> curve a->b
  int bf_count = 0;
  struct MapJob {  // one patch's harmonic map: its triangles and fixed boundary
    int patch = 0;
    Eigen::MatrixXd V;  // the patch's local vertices
    std::vector<int> bnd;
    Eigen::MatrixXd bc;
    parametrization::HarmonicMapResult result;
    std::exception_ptr error;
  };
  std::vector<MapJob> jobs;
  std::vector<int> local_of(S.V.rows(), -1);  // surface vertex -> local vertex of the current patch
  for (const auto& [vs, users] : faces) {
    if (users.size() > 2)
      throw GeometryError("structure face (vertices " + vertex_list(vs) + ") is shared by " + std::to_string(users.size()) + " blocks");
    if (users.size() == 2) continue;
    const int b = users[0].first, f = users[0].second;
    const LocalFace& lf = local_faces(T.type(b)).first[f];
    auto it = patch_of_corners.find(vs);
    if (it == patch_of_corners.end())
      throw GeometryError("block " + std::to_string(b + 1) + " face " + std::to_string(f + 1) + " (vertices " + vertex_list(vs) +
                          ") is on the boundary but matches no patch: no patch has exactly these corners");
    const int p = it->second;
    const polycube::Patch& patch = layout.patches[p];
    if (patch_face[p] >= 0)
      throw GeometryError("patch " + std::to_string(p + 1) + " (label " + std::to_string(patch.label) + ") matches two boundary faces");
    patch_face[p] = bf_count++;
    boundary_face_patch[vs] = p;
    if (patch.num_loops != 1)
      throw GeometryError("patch " + std::to_string(p + 1) + " (label " + std::to_string(patch.label) + ") has " +
                          std::to_string(patch.num_loops) + " boundary loops: a patch must be a disk");
    // Face vertices in outward order and the loop's corners in loop order.
    std::vector<int> fv(lf.v, lf.v + lf.n);
    for (int& x : fv) x = T.cells(b, x);
    std::vector<int> lc;
    for (int li : patch.corners) lc.push_back(corner_vertex[layout.corner_of(patch.loop[li])]);
    const int m = lf.n;
    int dir = 0, rot = -1;
    for (int r = 0; r < m && rot < 0; ++r) {
      bool fwd = true, bwd = true;
      for (int i = 0; i < m; ++i) {
        fwd = fwd && lc[(r + i) % m] == fv[i];
        bwd = bwd && lc[((r - i) % m + m) % m] == fv[i];
      }
      if (fwd) { rot = r; dir = 1; } else if (bwd) { rot = r; dir = -1; }
    }
    if (rot < 0)
      throw GeometryError("patch " + std::to_string(p + 1) + " visits its corners in an order that does not match block " +
                          std::to_string(b + 1) + " face " + std::to_string(f + 1));
    PatchMap& pm = maps[p];
    pm.tris = patch.triangles;
    for (int i = 0; i < m; ++i) pm.domain[fv[i]] = domain_corner(m, i);
    // Boundary: each loop segment between corners, by arc length, onto the domain edge.
    std::vector<int> bnd;
    std::vector<Eigen::Vector2d> bpos;
    const int L = static_cast<int>(patch.loop.size());
    for (size_t ci = 0; ci < patch.corners.size(); ++ci) {
      const int s0 = patch.corners[ci], s1 = patch.corners[(ci + 1) % patch.corners.size()];
      const int len = ((s1 - s0) % L + L) % L == 0 ? L : ((s1 - s0) % L + L) % L;
      Curve cv;
      cv.p.push_back(S.V.row(patch.loop[s0]).transpose());
      cv.s.push_back(0);
      for (int k = 1; k <= len; ++k) {
        Vec3 q = S.V.row(patch.loop[(s0 + k) % L]).transpose();
        cv.s.push_back(cv.s.back() + (q - cv.p.back()).norm());
        cv.p.push_back(q);
      }
      const int va = lc[ci], vb = lc[(ci + 1) % m];
      const Eigen::Vector2d da = pm.domain[va], db = pm.domain[vb];
      for (int k = 0; k < len; ++k) {
        bnd.push_back(patch.loop[(s0 + k) % L]);
        const double t = cv.s.back() > 0 ? cv.s[k] / cv.s.back() : 0.0;
        bpos.push_back((1 - t) * da + t * db);
      }
      if (!curves.count({va, vb})) {
        Curve rev;
        rev.p.assign(cv.p.rbegin(), cv.p.rend());
        for (double x : cv.s) rev.s.insert(rev.s.begin(), cv.s.back() - x);
        curves[{va, vb}] = cv;
        curves[{vb, va}] = rev;
      }
    }
    (void)dir;
    // The patch with local vertex numbers (increasing with the surface's, so the linear system is
    // the one the whole surface's numbering gives), so that no per-patch array is surface-sized.
    for (int t : pm.tris)
      for (int k = 0; k < 3; ++k) pm.vertex.push_back(S.F(t, k));
    std::sort(pm.vertex.begin(), pm.vertex.end());
    pm.vertex.erase(std::unique(pm.vertex.begin(), pm.vertex.end()), pm.vertex.end());
    for (size_t i = 0; i < pm.vertex.size(); ++i) local_of[pm.vertex[i]] = static_cast<int>(i);
    MapJob job;
    job.patch = p;
    job.V.resize(static_cast<int>(pm.vertex.size()), 3);
    for (size_t i = 0; i < pm.vertex.size(); ++i) job.V.row(i) = S.V.row(pm.vertex[i]);
    pm.F.resize(static_cast<int>(pm.tris.size()), 3);
    for (size_t i = 0; i < pm.tris.size(); ++i)
      for (int k = 0; k < 3; ++k) pm.F(i, k) = local_of[S.F(pm.tris[i], k)];
    for (int& v : bnd) v = local_of[v];
    job.bnd = std::move(bnd);
    job.bc.resize(static_cast<int>(job.bnd.size()), 2);
    for (size_t i = 0; i < job.bnd.size(); ++i) job.bc.row(i) = bpos[i].transpose();
    jobs.push_back(std::move(job));
  }
  for (size_t p = 0; p < layout.patches.size(); ++p)
    if (patch_face[p] < 0)
      throw GeometryError("patch " + std::to_string(p + 1) + " (label " + std::to_string(layout.patches[p].label) +
                          ", " + std::to_string(layout.patches[p].triangles.size()) + " triangles) matches no boundary face of the structure");
  // The harmonic maps are independent: solved on `threads` threads, largest patches first; each
  // job writes only its own PatchMap, and errors are reported in matching order, so the output
  // does not depend on the thread count.
  {
    std::vector<int> order(jobs.size());
    for (size_t j = 0; j < jobs.size(); ++j) order[j] = static_cast<int>(j);
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return jobs[a].V.rows() > jobs[b].V.rows(); });
    parallel_for(static_cast<int>(order.size()), nthreads, [&](int q) {
      MapJob& job = jobs[order[q]];
      try {
        job.result = parametrization::harmonic_map(job.V, maps[job.patch].F, job.bnd, job.bc);
        if (job.result.flipped == 0) {
          PatchMap& pm = maps[job.patch];
          pm.uv = std::move(job.result.uv);
          build_grid(pm, S);
        }
      } catch (...) {
        job.error = std::current_exception();
      }
    });
    for (const MapJob& job : jobs) {
      if (job.error) std::rethrow_exception(job.error);
      if (job.result.flipped > 0)
        throw MeshingError("patch " + std::to_string(job.patch + 1) + " (label " + std::to_string(layout.patches[job.patch].label) +
                           "): the harmonic map flips " + std::to_string(job.result.flipped) +
                           " triangles even with mean-value weights");
      (job.result.weights == parametrization::Weights::Cotangent ? stats.cotangent_patches : stats.mean_value_patches)++;
    }
  }
  stats.boundary_faces = bf_count;
  tick("patch maps");
  log("matched " + std::to_string(bf_count) + " boundary faces to patches (" + std::to_string(stats.cotangent_patches) +
      " cotangent, " + std::to_string(stats.mean_value_patches) + " mean-value maps)");

  // Boundary edges of the structure: edges of boundary faces.
  std::set<std::pair<int, int>> boundary_edges;
  for (const auto& [vs, p] : boundary_face_patch) {
    (void)p;
    for (size_t i = 0; i < vs.size(); ++i)
      for (size_t j = i + 1; j < vs.size(); ++j) boundary_edges.insert({vs[i], vs[j]});
  }

  // ---- global nodes: lattice points shared through their weights on structure vertices
  const int n1 = n + 1;
  auto lidx = [&](int i, int j, int k) { return (k * n1 + j) * n1 + i; };
  std::vector<std::vector<int>> lattice(nb, std::vector<int>(n1 * n1 * n1, -1));
  KeyTable shared(static_cast<size_t>(nb) * 6 * n1 * n1);  // at most 6 faces of (n+1)^2 points per block
  std::vector<Key> node_key;       // weights of shared nodes (empty key for block-interior nodes)
  std::vector<int> node_block;     // block of a block-interior node, -1 for shared nodes
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
            id = shared.find_or_insert(key, static_cast<int>(node_key.size()), inserted);
            if (inserted) { node_key.push_back(key); node_block.push_back(-1); }
          } else {
            id = static_cast<int>(node_key.size());
            Key none;
            none.fill(-1);
            node_key.push_back(none);
            node_block.push_back(b);
          }
          lattice[b][lidx(i, j, k)] = id;
        }
  }
  const int nn = static_cast<int>(node_key.size());
  tick("node ids");
  Eigen::MatrixXd X = Eigen::MatrixXd::Zero(nn, 3);
  std::vector<char> known(nn, 0);
  NodeFreedom freedom;
  freedom.kind.assign(nn, NodeFreedom::Free);
  freedom.param.assign(nn, {0.0, 0.0});
  freedom.where.assign(nn, nullptr);

  // Vertices, edges and boundary-face nodes straight from their keys.
  for (int id = 0; id < nn; ++id) {
    if (node_block[id] >= 0) continue;
    const Key& k = node_key[id];
    int vs[4], ws[4], m = 0;
    for (int q = 0; q < 4 && k[q] >= 0; ++q, ++m) {
      vs[m] = static_cast<int>(k[q] >> 32);
      ws[m] = static_cast<int>(k[q] & 0xffffffff);
    }
    if (m == 1) {
      X.row(id) = P[vs[0]].transpose();
      known[id] = 1;
      if (vertex_corner[vs[0]] >= 0) freedom.kind[id] = NodeFreedom::Fixed;
    } else if (m == 2) {
      auto c = curves.find({vs[0], vs[1]});
      if (boundary_edges.count({vs[0], vs[1]}) && c != curves.end()) {
        X.row(id) = c->second.at(static_cast<double>(ws[1]) / N3).transpose();
        freedom.kind[id] = NodeFreedom::Curve;
        freedom.param[id] = {static_cast<double>(ws[1]) / N3, 0.0};
        freedom.where[id] = &c->second;
      } else {
        X.row(id) = ((ws[0] * P[vs[0]] + ws[1] * P[vs[1]]) / static_cast<double>(N3)).transpose();
      }
      known[id] = 1;
    } else {
      std::vector<int> sv(vs, vs + m);
      auto f = boundary_face_patch.find(sv);
      if (f == boundary_face_patch.end()) continue;  // interior face: filled below
      const PatchMap& pm = maps[f->second];
      Eigen::Vector2d uv = Eigen::Vector2d::Zero();
      for (int q = 0; q < m; ++q) uv += ws[q] * pm.domain.at(vs[q]);
      uv /= static_cast<double>(N3);
      X.row(id) = evaluate(pm, S, uv(0), uv(1)).transpose();
      known[id] = 1;
      freedom.kind[id] = NodeFreedom::Patch;
      freedom.param[id] = {uv(0), uv(1)};
      freedom.where[id] = &pm;
    }
  }

  tick("boundary nodes");

  // Harmonic fill of unknown lattice nodes: successive over-relaxation from a linear start.
  const double omega = 2.0 / (1.0 + std::sin(M_PI / std::max(2, n)));
  auto harmonic_fill = [&](const std::vector<int>& ids, const std::vector<std::vector<int>>& nbrs) {
    std::vector<int> todo;
    for (size_t q = 0; q < ids.size(); ++q)
      if (!known[ids[q]]) todo.push_back(static_cast<int>(q));
    const double tol = 1e-10 * diag;
    for (int sweep = 0; sweep < 50 + 20 * n && !todo.empty(); ++sweep) {
      double change = 0;
      for (int q : todo) {
        double s0 = 0, s1 = 0, s2 = 0;
        for (int r : nbrs[q]) {
          s0 += X(ids[r], 0);
          s1 += X(ids[r], 1);
          s2 += X(ids[r], 2);
        }
        const double inv = 1.0 / static_cast<double>(nbrs[q].size());
        const int i = ids[q];
        const double d0 = s0 * inv - X(i, 0), d1 = s1 * inv - X(i, 1), d2 = s2 * inv - X(i, 2);
        X(i, 0) += omega * d0;
        X(i, 1) += omega * d1;
        X(i, 2) += omega * d2;
        change = std::max(change, std::fabs(d0) + std::fabs(d1) + std::fabs(d2));
      }
      if (change < tol) break;
    }
    for (int q : todo) known[ids[q]] = 1;
  };
  // Linear start for unknown nodes of a block from its corners.
  auto linear_start = [&](int b) {
    const CellType t = T.type(b);
    int w[8];
    for (int k = 0; k <= n; ++k)
      for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) {
          if (!in_lattice(t, n, i, j, k)) continue;
          const int id = lattice[b][lidx(i, j, k)];
          if (known[id]) continue;
          const int nw = weights(t, n, i, j, k, w);
          Vec3 s = Vec3::Zero();
          for (int v = 0; v < nw; ++v) s += w[v] * P[T.cells(b, v)];
          X.row(id) = (s / static_cast<double>(N3)).transpose();
        }
  };

  // Interior faces: Coons patches (quads) or harmonic fill (triangles).
  std::set<std::vector<int>> done_faces;
  for (int b = 0; b < nb; ++b) {
    const CellType t = T.type(b);
    auto [lf, nlf] = local_faces(t);
    const int (*C)[3] = corner_table(t);
    linear_start(b);
    for (int f = 0; f < nlf; ++f) {
      std::vector<int> vs;
      for (int i = 0; i < lf[f].n; ++i) vs.push_back(T.cells(b, lf[f].v[i]));
      std::sort(vs.begin(), vs.end());
      if (boundary_face_patch.count(vs) || !done_faces.insert(vs).second) continue;
      // Lattice coordinates of the face's corners in this block.
      auto corner = [&](int i) { return Eigen::Vector3i(C[lf[f].v[i]][0] * n, C[lf[f].v[i]][1] * n, C[lf[f].v[i]][2] * n); };
      const Eigen::Vector3i c0 = corner(0), e1 = (corner(1) - c0) / n, e2 = (corner(lf[f].n == 4 ? 3 : 2) - c0) / n;
      auto at = [&](int s, int u) { Eigen::Vector3i p = c0 + s * e1 + u * e2; return lattice[b][lidx(p(0), p(1), p(2))]; };
      if (lf[f].n == 4) {
        for (int u = 1; u < n; ++u)
          for (int s = 1; s < n; ++s) {
            const double a = static_cast<double>(s) / n, c = static_cast<double>(u) / n;
            Vec3 x = (1 - c) * X.row(at(s, 0)).transpose() + c * X.row(at(s, n)).transpose() +
                     (1 - a) * X.row(at(0, u)).transpose() + a * X.row(at(n, u)).transpose() -
                     ((1 - a) * (1 - c) * X.row(at(0, 0)).transpose() + a * (1 - c) * X.row(at(n, 0)).transpose() +
                      (1 - a) * c * X.row(at(0, n)).transpose() + a * c * X.row(at(n, n)).transpose());
            X.row(at(s, u)) = x.transpose();
            known[at(s, u)] = 1;
          }
      } else {
        std::vector<int> ids;
        std::map<std::pair<int, int>, int> pos;
        for (int u = 0; u <= n; ++u)
          for (int s = 0; s + u <= n; ++s) { pos[{s, u}] = static_cast<int>(ids.size()); ids.push_back(at(s, u)); }
        std::vector<std::vector<int>> nbrs(ids.size());
        for (const auto& [su, q] : pos)
          for (const auto& d : kTriNb) {
            auto it = pos.find({su.first + d[0], su.second + d[1]});
            if (it != pos.end()) nbrs[q].push_back(it->second);
          }
        harmonic_fill(ids, nbrs);
      }
    }
  }

  tick("interior faces");

  // Block interiors: transfinite interpolation (hex) or harmonic fill (prism, tet). Each block
  // writes only its own interior nodes and reads its (known) boundary: blocks run in parallel.
  parallel_for(nb, nthreads, [&](int b) {
    const CellType t = T.type(b);
    const auto& L = lattice[b];
    if (t == CellType::Hex) {
      auto x = [&](int i, int j, int k) -> Vec3 { return X.row(L[lidx(i, j, k)]).transpose(); };
      for (int k = 1; k < n; ++k)
        for (int j = 1; j < n; ++j)
          for (int i = 1; i < n; ++i) {
            const double s = static_cast<double>(i) / n, u = static_cast<double>(j) / n, v = static_cast<double>(k) / n;
            Vec3 f = (1 - s) * x(0, j, k) + s * x(n, j, k) + (1 - u) * x(i, 0, k) + u * x(i, n, k) + (1 - v) * x(i, j, 0) + v * x(i, j, n);
            Vec3 e = (1 - u) * (1 - v) * x(i, 0, 0) + u * (1 - v) * x(i, n, 0) + (1 - u) * v * x(i, 0, n) + u * v * x(i, n, n) +
                     (1 - s) * (1 - v) * x(0, j, 0) + s * (1 - v) * x(n, j, 0) + (1 - s) * v * x(0, j, n) + s * v * x(n, j, n) +
                     (1 - s) * (1 - u) * x(0, 0, k) + s * (1 - u) * x(n, 0, k) + (1 - s) * u * x(0, n, k) + s * u * x(n, n, k);
            Vec3 c = Vec3::Zero();
            for (int q = 0; q < 8; ++q) {
              const int* cc = kHexCorner[q];
              c += (cc[0] ? s : 1 - s) * (cc[1] ? u : 1 - u) * (cc[2] ? v : 1 - v) * x(cc[0] * n, cc[1] * n, cc[2] * n);
            }
            X.row(L[lidx(i, j, k)]) = (f - e + c).transpose();
            known[L[lidx(i, j, k)]] = 1;
          }
    } else {
      std::vector<int> ids;
      std::vector<int> where(n1 * n1 * n1, -1);
      for (int k = 0; k <= n; ++k)
        for (int j = 0; j <= n; ++j)
          for (int i = 0; i <= n; ++i)
            if (in_lattice(t, n, i, j, k)) { where[lidx(i, j, k)] = static_cast<int>(ids.size()); ids.push_back(L[lidx(i, j, k)]); }
      std::vector<std::vector<int>> nbrs(ids.size());
      const int (*nb3)[3] = t == CellType::Wedge ? kWedgeNb : kTetNb;
      const int nnb = t == CellType::Wedge ? 8 : 12;
      for (int k = 0; k <= n; ++k)
        for (int j = 0; j <= n; ++j)
          for (int i = 0; i <= n; ++i) {
            if (!in_lattice(t, n, i, j, k)) continue;
            for (int d = 0; d < nnb; ++d) {
              const int a = i + nb3[d][0], c = j + nb3[d][1], e = k + nb3[d][2];
              if (in_lattice(t, n, a, c, e)) nbrs[where[lidx(i, j, k)]].push_back(where[lidx(a, c, e)]);
            }
          }
      harmonic_fill(ids, nbrs);
    }
  });

  tick("block interiors");

  // ---- cells
  // Every block makes n^3 cells, written straight into the result.
  mesh::Mesh result;
  const long long total_cells = static_cast<long long>(nb) * N3;
  result.cells.setConstant(total_cells, 8, -1);
  result.types.resize(total_cells);
  result.region.resize(total_cells);
  // Block b writes rows [b n^3, (b+1) n^3): blocks run in parallel.
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
  parallel_for(nb, nthreads, [&](int b) {
    Out out{result, b * N3, (b + 1) * N3};
    const CellType t = T.type(b);
    const auto& L = lattice[b];
    auto id = [&](int i, int j, int k) { return L[lidx(i, j, k)]; };
    if (t == CellType::Hex) {
      for (int k = 0; k < n; ++k)
        for (int j = 0; j < n; ++j)
          for (int i = 0; i < n; ++i) {
            int c[8];
            for (int q = 0; q < 8; ++q) c[q] = id(i + kHexCorner[q][0], j + kHexCorner[q][1], k + kHexCorner[q][2]);
            out.add(CellType::Hex, c, b + 1);
          }
    } else if (t == CellType::Wedge) {
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
    } else {
      // Regular refinement of the tet lattice: up tets, down tets, and octahedra split into four
      // tets along their shortest diagonal. Orientation is fixed in lattice space.
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
    if (out.at != out.end)
      throw MeshingError("generation: block " + std::to_string(b + 1) + " made " + std::to_string(out.at - b * N3) +
                         " cells, expected " + std::to_string(N3));
  });
  result.V = std::move(X);
  tick("cells");

  // ---- relaxation and untangling of the nodes inside the volume
  if (opt.relax_sweeps > 0) {
    freedom.now = freedom.param;
    freedom.place = [&](int v, const double* q, double* x) {
      Vec3 p = freedom.kind[v] == NodeFreedom::Curve ? static_cast<const Curve*>(freedom.where[v])->at(q[0])
                                                     : evaluate(*static_cast<const PatchMap*>(freedom.where[v]), S, q[0], q[1]);
      x[0] = p(0);
      x[1] = p(1);
      x[2] = p(2);
    };
    freedom.clamp = [&](int v, double* q) {
      const double e = 1e-6;
      if (freedom.kind[v] == NodeFreedom::Curve) {
        q[0] = std::clamp(q[0], e, 1 - e);
        return;
      }
      q[0] = std::clamp(q[0], e, 1 - e);
      q[1] = std::clamp(q[1], e, 1 - e);
      if (static_cast<const PatchMap*>(freedom.where[v])->domain.size() == 3 && q[0] + q[1] > 1 - e) {
        const double shift = 0.5 * (q[0] + q[1] - (1 - e));
        q[0] -= shift;
        q[1] -= shift;
      }
    };
    // Boundary nodes slid to enlarge the enclosed volume (an experiment, off by default: see
    // GenerateOptions::volume_slide).
    if (opt.volume_slide > 0) log(slide_for_volume(result, freedom, opt.volume_slide, 0.3, 0.45 / n));
    // The plain relaxation, then the untangling of the cells it leaves inverted: first with
    // surface nodes within a fifth of a lattice step of where they were made, then, for what is
    // left, within 0.45 of a step. Nodes away from inverted cells keep the plain relaxation's
    // positions exactly.
    std::vector<int> left;
    const Adjacency adj = node_cells(result);
    log(relax_poor(result, adj, freedom.kind, opt.relax_sweeps, 0.2, nthreads, opt.untangle ? &left : nullptr, 0.0));
    if (opt.untangle)
      for (double box : {0.2, 0.45}) {
        if (left.empty()) break;
        const std::vector<int> candidates = left;
        log(untangle_nodes(result, adj, freedom, opt.relax_sweeps, 0.0, 0.2, 0.0, box / n, &candidates, &left));
      }
  }
  tick("relaxation");
  log(timing);
  if (stats_out) *stats_out = stats;
  return result;
}

}  // namespace hexdom::generation
