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
  /// Untangle instead of the plain relaxation: a node next to a poor cell moves only when the worst
  /// Jacobian sample that depends on it rises (so inverted cells can improve step by step), nodes
  /// descend a penalty on poor samples, and boundary nodes next to cells at most 0.05 slide in their
  /// patch or along their curve, staying on the input triangles. Leaves far fewer inverted cells
  /// (all six paper models at level 2: 0 but 3 prisms of ant, against 113 cells) but the
  /// improvement stage, tuned on the plain relaxation's output, ends lower on some models, so it is
  /// off by default.
  bool untangle = false;
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
/// neighbourhood's worst (or the untangling, see GenerateOptions::untangle). Cell region = 1-based
/// block number. Logs
/// (info) the matching, the relaxation's work and the CPU time of each stage.
/// Throws GeometryError for a non-manifold or open surface, a face matching no patch, a patch
/// matching no face, a corner no structure vertex reaches, or a patch that is not a disk with 3 or
/// 4 corners; std::invalid_argument-free: a bad level is a GeometryError too.
mesh::Mesh generate(const mesh::SurfaceMesh& patches, const mesh::Mesh& structure,
                    const GenerateOptions& options = {}, GenerateStats* stats = nullptr);

}  // namespace hexdom::generation
