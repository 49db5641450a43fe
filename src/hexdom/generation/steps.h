// Internal to generation: the state generate() passes through its steps, and the steps, in the
// order generate() runs them. Each step reads what the earlier ones wrote and fills its own part.
#pragma once

#include <Eigen/Core>
#include <chrono>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "hexdom/generation/block_lattice.h"
#include "hexdom/generation/generate.h"
#include "hexdom/generation/patch_maps.h"
#include "hexdom/optimize/relax_nodes.h"
#include "hexdom/polycube/patch_layout.h"

namespace hexdom::generation {

struct GenerationState {
  GenerationState(const mesh::SurfaceMesh& surface, const mesh::Mesh& structure, const GenerateOptions& options);

  const mesh::SurfaceMesh& S;  ///< the segmented surface
  const mesh::Mesh& T;         ///< the structure (blocks)
  const GenerateOptions& opt;
  int n = 1, n1 = 2;           ///< cells per block edge, lattice points per block edge
  long long N3 = 1;            ///< n^3: cells per block, and the sum of a lattice point's weights
  int nthreads = 1;
  GenerateStats stats;

  // Surface (layout_surface)
  polycube::PatchLayout layout;
  double diag = 0;  ///< the surface's bounding-box diagonal

  // Structure vertices (snap_structure)
  std::vector<Vec3> P;             ///< structure vertex positions, corners snapped onto the surface
  std::vector<int> corner_vertex;  ///< surface corner -> structure vertex
  std::vector<int> vertex_corner;  ///< structure vertex -> surface corner, -1 for interior vertices

  // Boundary faces matched to patches (match_faces, then solve_patch_maps)
  std::vector<PatchMap> maps;                              ///< per patch
  std::map<std::vector<int>, int> boundary_face_patch;     ///< sorted face vertices -> patch
  std::map<std::pair<int, int>, Curve> curves;             ///< (structure vertex a, b) -> curve a -> b
  std::set<std::pair<int, int>> boundary_edges;            ///< edges of boundary faces (a < b)
  std::vector<MapJob> jobs;                                ///< the patches' harmonic maps to solve

  // Nodes (number_nodes, then the fill steps)
  std::vector<std::vector<int>> lattice;  ///< per block: lattice point -> node id
  std::vector<Key> node_key;              ///< weights of shared nodes (all -1 for block-interior nodes)
  std::vector<int> node_block;            ///< block of a block-interior node, -1 for shared nodes
  Eigen::MatrixXd X;                      ///< node positions
  std::vector<char> known;                ///< per node: position set
  optimize::NodeFreedom freedom;          ///< how each node may move in the relaxation
  std::vector<const Curve*> on_curve;     ///< per node: the curve of a Curve node
  std::vector<const PatchMap*> on_patch;  ///< per node: the patch of a Patch node

  mesh::Mesh result;

  int lidx(int i, int j, int k) const { return lattice_index(n1, i, j, k); }
  void log(const std::string& message) const;
  /// Adds the wall-clock time since the last tick to the timing line under `stage`.
  void tick(const char* stage);
  std::string timing = "stage times (ms):";

 private:
  std::chrono::steady_clock::time_point t_last_;
};

// match_structure.cpp
/// The surface's closedness check and patch layout.
void layout_surface(GenerationState& g);
/// Checks the blocks and snaps structure vertices onto the surface corners within the tolerance.
void snap_structure(GenerationState& g);
/// Matches every boundary face of the structure to the patch with its corners, and prepares the
/// patches' harmonic-map jobs and the curves between corners.
void match_faces(GenerationState& g);
/// Solves the harmonic maps, throws for a failed one, counts the weights used.
void map_patches(GenerationState& g);

// assembly.cpp
/// Node ids of every block's lattice points, shared through their weights on structure vertices.
void number_nodes(GenerationState& g);
/// The cells of every block into g.result (n^3 per block, block order), then the node positions.
void make_cells(GenerationState& g);

// fill.cpp
/// Structure vertices, edges and boundary-face nodes placed from their keys (on the surface for
/// boundary faces and edges); sets their freedom.
void place_boundary_nodes(GenerationState& g);
/// Interior faces: Coons patches (quads) or harmonic fill (triangles), from a linear start.
void fill_interior_faces(GenerationState& g);
/// Block interiors: transfinite interpolation (hex) or harmonic fill (prism, tet), in parallel.
void fill_block_interiors(GenerationState& g);

}  // namespace hexdom::generation
