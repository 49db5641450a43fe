// The whole automatic path from a closed triangle surface to a hex mesh: segmentation, automatic
// polycube, generation and quality improvement, one call.
#pragma once

#include <string>

#include "hexdom/autopolycube/autopolycube.h"
#include "hexdom/common/error.h"
#include "hexdom/mesh/mesh.h"
#include "hexdom/quality/improve.h"
#include "hexdom/quality/report.h"
#include "hexdom/segmentation/segment_cvt.h"

namespace hexdom::autopolycube {

struct MeshSurfaceOptions {
  double size = 0;  ///< target element size H; 0: the bounding-box diagonal / 30
  int level = 1;    ///< subdivision level s: blocks are grid cells of h = H * 2^s, 2^s cells per block edge
  segmentation::CvtOptions segment;   ///< segmentation (its log is replaced by `log` when `verbose`)
  AutoPolycubeOptions polycube;       ///< its size and level are taken from above
  int relax_sweeps = 10;              ///< generation's relaxation sweeps
  bool improve = true;                ///< run the improvement stage (recommended sequence)
  quality::ImproveOptions improvement;  ///< its surface is the patch surface
  /// One line per stage (level 0); with `verbose` also the stages' own messages.
  LogCallback log;
  bool verbose = false;
};

struct MeshSurfaceRun {
  mesh::SurfaceMesh labels;   ///< the segmentation (label 1..6 per triangle of the input)
  AutoPolycube polycube;      ///< structure, patch surface, repaired labels, polycube surface
  mesh::Mesh generated;       ///< the mesh as generated
  mesh::Mesh mesh;            ///< the final mesh (improved, unless improve is off)
  quality::QualityReport generated_quality, quality;
  double seconds[4] = {0, 0, 0, 0};  ///< segment, autopolycube, generate, improve
  std::string stage;          ///< the stage running last ("segment", "autopolycube", "generate", "improve", "done")
};

/// Runs segment -> autopolycube -> generate -> improve on `surface` (closed, oriented outward; its
/// patch ids are CAD faces when there are several, see CvtOptions::respect_faces). When `progress`
/// is given it holds, also when this throws, what the finished stages produced. Inverted cells that
/// remain are reported in `quality`, not thrown. Throws what the stages throw.
MeshSurfaceRun mesh_surface(const mesh::SurfaceMesh& surface, const MeshSurfaceOptions& options = {},
                            MeshSurfaceRun* progress = nullptr);

/// "segment: 12 charts in 0.21 s"-style summary of a run, one line per finished stage.
std::string to_text(const MeshSurfaceRun& run);

}  // namespace hexdom::autopolycube
