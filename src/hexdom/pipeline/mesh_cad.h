// A CAD part meshed with no manual step: tessellate, the automatic path (pipeline::mesh_surface),
// then the boundary nodes snapped onto the B-rep (snap.h). The tessellation is only a means: when
// its labelling defeats the automatic polycube, or cells stay inverted after the snap, the B-rep is
// tessellated again with slightly smaller, then larger triangles (the polycube grid keeps the first
// element size) and the better mesh kept. `hexdom mesh` and _hexdom's mesh_part run this.
#pragma once

#include <array>
#include <vector>

#include "hexdom/pipeline/mesh_surface.h"
#include "hexdom/cad/shape.h"
#include "hexdom/cad/snap.h"
#include "hexdom/cad/tessellate.h"
#include "hexdom/common/error.h"
#include "hexdom/mesh/mesh.h"

namespace hexdom::pipeline {

struct MeshCadOptions {
  cad::TessellateOptions tessellation;          ///< its size: the triangles' (0: see cad::TessellateOptions)
  MeshSurfaceOptions mesh;   ///< its size: the polycube grid's (0: mesh_surface's default)
  /// Triangle sizes, times the first tessellation's, of the tessellations tried in turn when the
  /// first one's mesh could not be made (a labelling the repair cannot use, a cut that fails) or
  /// keeps inverted cells; the first that gives a mesh without inverted cells ends the search, the
  /// best by the candidates' order (pipeline::better_run) is kept. Method::Auto: not when the
  /// overlay's mesh was kept (another tessellation's polycube did better on none of 23 corpus parts).
  std::vector<double> retessellate = {0.97, 1.03, 0.94, 1.06};
  /// When the first tessellation gave a mesh, only with inverted cells, only this many of them are
  /// tried (each try is a whole run).
  int retessellate_inverted = 2;
  /// Cell sizes along CAD edges: (edge id, FreeCAD's Edge{id}; size). Each edge's points
  /// (cad::edge_points, a quarter of the size apart) become a polyline local size of
  /// mesh.overlay.local_sizes (the overlay path then meshes the part, as for sizes on faces).
  std::vector<std::pair<int, double>> edge_sizes;
  bool snap = true;          ///< snap the boundary nodes onto the B-rep (each tessellation's mesh)
  cad::SnapOptions snap_options;
  LogCallback log;  ///< one line per new tessellation
};

struct MeshCadRun {
  mesh::SurfaceMesh surface;        ///< the tessellation the kept mesh was made from
  cad::TessellateStats stats;            ///< its figures
  /// The kept run as mesh_surface gives it, but for `mesh` and `quality`: after the snap when `snapped`.
  pipeline::MeshSurfaceRun run;
  bool snapped = false;
  /// When `snapped`: run.mesh and run.quality as mesh_surface gave them, before the snap
  /// (Method::Auto's step 3 starts the polycube's further candidates from that run).
  mesh::Mesh unsnapped_mesh;
  quality::QualityReport unsnapped_quality;
  cad::SnapResult snap;                  ///< the snap's report, quality and node kinds, when snapped (its mesh is run.mesh)
  double snap_seconds = 0;
  double tessellation_factor = 1;   ///< its triangle size over the first tessellation's
  int tessellations = 0;            ///< tessellations made
};

/// Tessellates `shape` and meshes the surface (see MeshCadOptions::retessellate). Each tessellation is
/// checked once first (mesh::check_solid_surface, when options.mesh.check_input; its warnings go to
/// options.log); one it refuses counts as a tessellation the paths could not use. When `progress`
/// is given it holds, also when this throws, the first tessellation and what its run produced (for
/// the files written for inspection). Throws the first tessellation's error when no tessellation
/// gives a mesh; inverted cells that remain are reported in run.quality, not thrown.
/// The polycube path's time budget (options.mesh.polycube_seconds, or options.mesh.deadline) covers
/// every polycube attempt of the call, retessellations included: one deadline, made when the first
/// tessellation is done (that one serves the overlay path as well; a deadline given in
/// options.mesh.deadline is used as it is).
/// Once it has passed no further tessellation is tried for the polycube path (the log says so) and
/// the best mesh so far is kept; a TimeoutError is thrown only with Method::Polycube and a deadline,
/// when it passes on the first tessellation before any mesh exists. InterruptedError once the
/// calling thread's interrupt is raised (common/interrupt.h), as mesh_surface; TimeoutError past
/// options.mesh.time_limit (the whole call: tessellations, paths, snap, second order).
/// Numbers: local sizes on faces and edges are taken, and the result's surface patches and snapped
/// entities given, in the numbers of the shape the solid was read from (cad::source_numbers: a
/// compound's, FreeCAD's for the whole shape); InputError for a face or edge not of this solid. The
/// run `progress` holds when this throws is in the solid's own numbers.
MeshCadRun mesh_cad_part(const cad::Shape& shape, const MeshCadOptions& options = {}, MeshCadRun* progress = nullptr);

/// Several solids (a CAD file's, cad::read_solids) meshed one by one by mesh_cad_part with the same
/// options.
struct MeshSolidsRun {
  /// The whole part as one run, numbered as the source (a compound's faces, edges and vertices as
  /// FreeCAD numbers them, cad::source_numbers): run the solids' runs put together
  /// (merge_solid_runs: the cells of solid k in region k, solids sharing no node, its quality the
  /// whole mesh's); surface the solids' tessellations, each triangle's patch the source's face
  /// number; snap, when every solid was snapped, the node kinds and entities (source numbers) in
  /// run.mesh's node order, the report over all boundary nodes and the quality run.quality
  /// (snap.mesh is empty: it is run.mesh); stats, snap_seconds and tessellations summed (stats.brep_volume the solids'
  /// volumes), tessellation_factor the first solid's.
  MeshCadRun part;
  std::vector<MeshCadRun> solids;              ///< each solid's own run (also in the source's numbers)
  std::vector<std::array<int, 2>> touching;    ///< pairs of solids that touch (cad::touching_solids)
};

/// Meshes every solid of `solids` (cad::read_solids; mesh_cad_part each, options.mesh.time_limit
/// over them all). Local sizes on faces (options.mesh.overlay.local_sizes without polyline) and
/// edges (options.edge_sizes) are given in the source's numbers and reach the solid that has the
/// face or edge; InputError when no solid has it. Logs (options.log) a warning for each pair that
/// touches: their meshes do not conform there. Throws the first solid's error that has no mesh, the
/// message prefixed "solid k: "; `progress`, when given, holds the solids meshed so far.
MeshSolidsRun mesh_cad_solids(const std::vector<cad::Shape>& solids, const MeshCadOptions& options = {},
                              MeshSolidsRun* progress = nullptr);

}  // namespace hexdom::pipeline
