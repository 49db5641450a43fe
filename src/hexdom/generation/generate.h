// Hex-dominant mesh generation from a segmented surface and a polycube structure (the original
// HexGen, PrismGen and TetGen in one conforming run).
#pragma once

#include "hexdom/common/error.h"
#include "hexdom/mesh/mesh.h"

namespace hexdom::generation {

struct GenerateOptions {
  int level = 2;  ///< subdivision level s: 2^s cells per block edge, 8^s cells per block (0..6)
  /// Structure vertices within snap_tolerance x (bounding-box diagonal) of a surface corner are
  /// snapped to it; the others are interior vertices.
  double snap_tolerance = 1e-4;
  /// Sweeps of the validity-preserving relaxation of nodes inside the volume next to poor cells
  /// (scaled Jacobian <= 0.2); 0: none. The improvement stage does the thorough work.
  int relax_sweeps = 10;
  /// After the plain relaxation, untangle the cells it leaves inverted (optimize::untangle_nodes):
  /// only nodes of inverted cells (and, while cells stay inverted, of the cells around them) move; a
  /// move is kept only when the worst Jacobian sample that depends on the node rises; nodes descend
  /// a penalty on samples below 0.2; surface nodes of inverted cells slide in their patch or along
  /// their curve, staying on the input triangles, first within 0.2 then within 0.45 of a lattice
  /// step of where they were made. Every other node keeps the plain relaxation's position. Cells
  /// may stay inverted; the improvement stage takes them on.
  bool untangle = true;
  /// Threads for the patches' harmonic maps, the block interiors, the cells and the search for poor
  /// cells (0: one per hardware thread). The output does not depend on it.
  int threads = 0;
  LogCallback log;
};

struct GenerateStats {
  int boundary_faces = 0, patches = 0, corners = 0, interior_vertices = 0;
  int cotangent_patches = 0, mean_value_patches = 0;  ///< harmonic-map weights that were used
};

/// Builds the mesh: every boundary face of the structure is matched to the patch (connected region
/// of one id of `patches`) whose corners are the face's vertices; each patch is mapped harmonically
/// onto its face; hex blocks are split into (2^s)^3 hexes, prism blocks into 8^s prisms, tet blocks
/// into 8^s tets, sharing nodes on shared block edges and faces. Boundary nodes lie on the input
/// triangles; the rest come from transfinite (hex) or discrete harmonic (prism, tet) interpolation
/// of the block boundaries, then a relaxation that never lowers a cell's scaled Jacobian below its
/// neighbourhood's worst (optimize::relax_poor), then the untangling of inverted cells (see
/// GenerateOptions::untangle). Neither lowers the worst cell of the mesh; neither guarantees that no
/// cell stays inverted.
/// Cell region = 1-based block number. The patch maps, block interiors and cells are computed on
/// GenerateOptions::threads threads; the result does not depend on their number. Logs (info) the
/// matching, the relaxation's work and the wall-clock time of each stage.
/// Throws GeometryError for a non-manifold or open surface, a face matching no patch, a patch
/// matching no face, a corner no structure vertex reaches, or a patch that is not a disk with 3 or
/// 4 corners; std::invalid_argument-free: a bad level is a GeometryError too. Throws MeshingError
/// when a patch's harmonic map flips triangles even with mean-value weights.
mesh::Mesh generate(const mesh::SurfaceMesh& patches, const mesh::Mesh& structure,
                    const GenerateOptions& options = {}, GenerateStats* stats = nullptr);

}  // namespace hexdom::generation
