// The whole automatic path from a closed triangle surface to a hex mesh: segmentation, automatic
// polycube, generation and quality improvement, one call.
#pragma once

#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "hexdom/autopolycube/autopolycube.h"
#include "hexdom/common/deadline.h"
#include "hexdom/common/error.h"
#include "hexdom/mesh/mesh.h"
#include "hexdom/optimize/curve_mid_nodes.h"
#include "hexdom/optimize/improve.h"
#include "hexdom/overlay/overlay.h"
#include "hexdom/quality/report.h"
#include "hexdom/segmentation/cube_frame.h"
#include "hexdom/segmentation/segment_cvt.h"

namespace hexdom::pipeline {

/// Which meshing path runs: the polycube (segment -> autopolycube -> generate -> improve), the
/// overlay grid (overlay::overlay_mesh), or the polycube and, when it fails or its mesh misses a
/// target (an inverted cell, a worst SJ below target_sj, a volume off by more than target_volume),
/// the overlay grid too (also when its largest edge ratio passes target_edge_ratio), the better kept
/// by better_run.
enum class Method { Auto, Polycube, Overlay };

/// "auto", "polycube", "overlay"; and back (throws InputError naming the word for another one).
std::string method_name(Method m);
Method method_from_name(const std::string& name);

struct MeshSurfaceRun;
struct Stretch;

struct MeshSurfaceOptions {
  Method method = Method::Auto;
  /// Threads of the generation and of every optimiser run (polycube improvement, overlay, the snap's
  /// restoration); 0: one per core. The meshes do not depend on it. (Under auto the two paths also
  /// run beside each other.)
  int threads = 0;
  /// The polycube path's time budget in Method::Auto, in seconds from the call (0: no limit), so
  /// that auto falls back to the overlay path quickly where the polycube path takes long. It is
  /// looked at between the segmentation's retries and between the stages, inside autopolycube (label
  /// repair, chart maps, sliver strips) and after each improvement round, and before each further
  /// candidate. Where no polycube mesh exists yet the path stops with TimeoutError, which auto
  /// treats as any failure of the polycube path (the overlay runs; polycube_note names the budget and
  /// the stage); once a mesh exists the improvement ends early and no further candidate is tried,
  /// the run so far kept (MeshSurfaceRun::budget_passed). Method::Polycube ignores it (no limit: the
  /// path asked for runs to its end) unless `deadline` is set; the program's --polycube-seconds and
  /// the module's polycube_seconds=, when given with the polycube method, set `deadline` from it.
  /// Method::Overlay: not used (the overlay path has no budget).
  double polycube_seconds = 20;
  /// Seconds of wall time the whole call (mesh_surface, mesh_cad_part) may take; 0: no limit.
  /// Past it the call stops within a fraction of a second and throws TimeoutError naming the step
  /// that was running (common/time_limit.h); nothing is returned. The default, half an hour, is
  /// far above what any part has needed: a bound against a run that never ends, not a budget.
  double time_limit = 1800;
  /// Method::Auto (pipeline/choice.h): seconds from the start of the choice after which a path
  /// that still runs is stopped when the other one has a mesh that meets every target: the
  /// polycube's first candidate when the overlay's mesh does, the edge ratio aside (meets_targets;
  /// it keeps what it has) and its further candidates then (what they have counts for nothing),
  /// the overlay when the polycube's further candidates' mesh does
  /// (meets_path_targets). Paths that end before it are chosen between as without it. 0: no such stop.
  double polycube_seconds_overlay_met = 5;
  /// When set, the polycube path's deadline in Auto and Polycube, instead of polycube_seconds: a
  /// moment fixed by the caller (mesh_cad_part sets it once for all its tessellations). With
  /// Method::Overlay, when set, the overlay path stops with TimeoutError once it passes or is
  /// cancelled (auto runs the overlay with a cancellable one of its own, no time limit).
  Deadline deadline;
  /// The overlay path's options; its size, alignment and log are taken from here. Its local_sizes
  /// (cell sizes on faces) are met by both paths: the overlay's octree, the polycube's refinement by
  /// thirds (local_refinement.h).
  overlay::OverlayOptions overlay;
  double size = 0;  ///< target element size H; 0: the bounding-box diagonal / 30 (see max_size, min_size)
  /// Bounds on the element size (0: none), as FreeCAD's Gmsh mesher's CharacteristicLengthMax / Min:
  /// H (given or default) is brought within [min_size, max_size] (bounded_size), and the cells made
  /// thinner than H for a thin part (across_thin, the overlay's grid, its halvings and octree) are
  /// not made shorter than min_size, so such a part may get fewer than across_thin cells across.
  /// min_size > max_size is an InputError.
  double max_size = 0;
  double min_size = 0;
  int level = 1;    ///< subdivision level s: blocks are grid cells of h = H * 2^s, 2^s cells per block edge
  segmentation::CvtOptions segment;   ///< segmentation (its log is replaced by `log` when `verbose`)
  /// Its size and level are taken from above. The candidates after the first (without the widths of
  /// holes, level s - 1) get the first one's repaired labelling (AutoPolycubeOptions::repaired) for
  /// the edge weight it took, so the label repair runs once per run, not once per candidate.
  autopolycube::AutoPolycubeOptions polycube;
  /// When autopolycube cannot use the segmentation, segment again with these edge weights (lambda)
  /// in turn, then give up with the first attempt's error. Smoother labellings have fewer small
  /// charts for the label repair to merge.
  std::vector<double> retry_edge_weights = {1.0, 0.3, 3.0};
  /// Method::Polycube: when set, the first candidate's run, already made with these options (auto's
  /// first run, before any snap): the candidates start from it instead of meshing it again.
  const MeshSurfaceRun* first_run = nullptr;
  /// Set by the polycube path for a part it meshes stretched (stretch.h; the surface given is then
  /// the stretched one): generation takes the polycube's structure and patch surface rounded
  /// through the model's coordinates, stretched(unstretched(x)), as a rebuild from what the run
  /// reports (mapped back) takes them, so that the rebuild gives the same mesh bit for bit.
  const Stretch* stretched_by = nullptr;
  int relax_sweeps = 10;              ///< generation's relaxation sweeps
  bool improve = true;                ///< run the improvement stage (recommended sequence)
  optimize::ImproveOptions improvement;  ///< its surface is the patch surface
  /// When inverted cells remain after improvement at level s > 0, run again from the polycube on
  /// with level s - 1 (the same element size, a grid of half the spacing, so thin features get their
  /// own cells) and keep the better result.
  bool refine_when_inverted = true;
  /// The same at level s > 0 when no cell is inverted but the worst scaled Jacobian is below this
  /// (by default target_sj's 0.3): a finer grid follows thin or crowded features. The finer run is
  /// kept only when it is better by the candidates' order (see try_without_widths). 0: only when
  /// cells are inverted.
  double refine_below_sj = 0.3;
  /// The polycube keeps the widths of holes (AutoPolycubeOptions::keep_widths, on in `polycube`);
  /// when the mesh then misses a target (an inverted cell, a worst scaled Jacobian below target_sj,
  /// a volume off the input surface's by more than target_volume), run again with the least-squares
  /// plane offsets and keep the better mesh: fewer inverted cells; then the one whose worst SJ meets
  /// target_sj; then the one whose volume meets target_volume; then the one within
  /// target_edge_ratio; then the higher worst SJ.
  bool try_without_widths = true;
  /// When apexes got tet and prism blocks (AutoPolycubeOptions::collapse_apexes) and the mesh misses a
  /// target, mesh the hex blocks under the caps too and keep the better by the same order.
  bool try_hex_apexes = true;
  double target_sj = 0.3;       ///< worst scaled Jacobian the candidates are measured against
  double target_volume = 0.01;  ///< relative volume error the candidates are measured against
  /// Largest edge ratio (longest over shortest edge of one cell, quality::max_edge_ratio) the paths
  /// are measured against: in Method::Auto a polycube mesh above it (a cell layer much thinner than
  /// the element size, from a feature far smaller than it) has the overlay path run too, and of two
  /// meshes equal on the other targets the one within it is kept. 0: not looked at.
  double target_edge_ratio = 10;
  /// Segment and build the polycube in the frame the faces fit best (cube_frame), so that a part
  /// lying at an angle is meshed as if square to the axes; a part the model's axes already fit (by
  /// `frame_options.min_gain`) is left as it is. Ignored when `segment.frame` or `polycube.frame`
  /// is given (not the identity): that frame is used. Every output is in the input's coordinates.
  bool align = true;
  segmentation::CubeFrameOptions frame_options;
  /// The polycube path on a part thin along an axis of its frame (a plate, a rod: an extent whose
  /// across_thin cells would be shorter than the element size over max_cell_ratio, needles for cubic
  /// cells of that size, one block thick): cells of a different length along each frame axis,
  /// at least across_thin across every extent and none longer than max_cell_ratio times the
  /// shortest (overlay::grid_spacing, as the overlay's grid), so that the thin axis gets cells across
  /// without needles along the others. Made by meshing the part stretched along its thin axes
  /// (candidates and improvement there) and mapping the results back; `size` then bounds the longest
  /// side. across_thin 0: cubic cells (the part's thin axis gets one block). The overlay path's grid
  /// takes across_thin + 1 cells across (OverlayOptions::across; its buffer layers add one more on
  /// each side), or OverlayOptions::across as given for across_thin 0.
  double across_thin = 2;
  double max_cell_ratio = 5;
  /// Element order of the result: 1 (hex8, wedge6, tet4) or 2 (hex20, wedge15, tet10: the first-order
  /// mesh made, then a node on every cell edge, those of the boundary on the input surface, or on
  /// the B-rep in mesh_cad_part; see optimize::second_order_on_surface, cad::second_order_on_brep).
  /// The paths and their choices work on the first-order mesh. Others: InputError.
  int order = 1;
  optimize::CurveOptions curve;  ///< order 2: how far a cell may lose quality to its curved edges
  /// Check the input first (mesh::check_solid_surface: closed, consistently oriented, no
  /// crossing triangles, shells facing out of the solid; a shell facing the wrong way is turned
  /// around with a warning, level 1); `input_name` names the input in its messages.
  bool check_input = true;
  std::string input_name = "the surface";
  /// One line per stage (level 0); with `verbose` also the stages' own messages.
  LogCallback log;
  bool verbose = false;
};

/// With Method::Overlay under Method::Auto, `labels`, `polycube`, `edge_weight`, `level`,
/// `keep_widths` and `collapse_apexes` are the polycube path's attempt (what its finished stages
/// made, possibly nothing), so that a front end can show the stages the overlay mesh was preferred
/// to; `generated`, `mesh` and the qualities are the overlay's.
/// How a mesh's cells compare with the local sizes asked (local_size_fit, local_refinement.h).
struct LocalSizeFit {
  /// Per local size, in the options' order: the median size of the mesh's cells on its face (or
  /// along its polyline) over the size asked; 0 where no cell lies there.
  std::vector<double> ratio;
  int met = 0;  ///< of them, those met (within)
  bool all_met() const { return met == static_cast<int>(ratio.size()); }
  /// A size is met when the cells there are within 20% of it.
  static bool within(double ratio) { return std::abs(ratio - 1) <= 0.2; }
};

struct MeshSurfaceRun {
  Method method = Method::Polycube;   ///< the path that made `mesh` (Polycube or Overlay)
  overlay::OverlayResult overlay;     ///< the overlay path's figures when it made `mesh` (its mesh moved out)
  /// In auto mode: the first line of the polycube path's error when it gave no mesh, or what its mesh
  /// missed when the overlay was tried too (with local sizes the overlay is always tried: then its
  /// figures); empty otherwise.
  std::string polycube_note;
  mesh::SurfaceMesh labels;   ///< the segmentation (label 1..6 per triangle of the input)
  autopolycube::AutoPolycube polycube;      ///< structure, patch surface, repaired labels, polycube surface
  mesh::Mesh generated;       ///< the mesh as generated
  mesh::Mesh mesh;            ///< the final mesh (improved, unless improve is off)
  quality::QualityReport generated_quality, quality;
  double seconds[4] = {0, 0, 0, 0};  ///< segment, autopolycube, generate, improve
  double edge_weight = 0;     ///< the segmentation's lambda that autopolycube took
  int level = 0;              ///< the subdivision level of the result (see refine_when_inverted)
  /// The polycube options of the kept candidate (see try_without_widths, try_hex_apexes): with
  /// edge_weight and level they rebuild its polycube (autopolycube on the labels segmented with
  /// edge_weight, AutoPolycubeOptions::keep_widths, collapse_apexes, level).
  bool keep_widths = true;
  bool collapse_apexes = true;
  /// The frame the labels and the polycube refer to (see align); rotation the identity when the
  /// part was meshed in its own axes.
  segmentation::CubeFrame frame;
  /// The factors a thin part was stretched by along the frame's axes (x_stretched = stretch .*
  /// (frame.rotation x), stretch.h) for its segmentation, polycube, generation and improvement,
  /// whose results here are mapped back; ones when it was not stretched.
  Eigen::Vector3d stretch = Eigen::Vector3d::Ones();
  int segmentations = 0;      ///< segmentations tried
  /// The polycube path's deadline passed after it had a mesh: the improvement stopped early or
  /// candidates were left untried; the mesh is the best one made in the time.
  bool budget_passed = false;
  /// Method::Auto: the polycube path's first run gave a mesh (whether kept or not). Without one
  /// (its labelling defeated the repair, or its time ran out) another tessellation may still give
  /// a polycube (mesh_cad_part); with one, another tessellation seldom gives a better one.
  bool polycube_meshed = false;
  std::string stage;          ///< the stage running last ("segment", "autopolycube", "generate", "improve", "done")
  /// The volume the input surface encloses, its shells facing as the input check turned them (the
  /// reference a mesh's volume is compared with); set by mesh_surface when it returns.
  double surface_volume = 0;
  /// A surface bounding several solids (separate closed shells, each with its cavities): each
  /// solid's own run, in the order mesh::check_solid_surface numbers them; `mesh` and `generated`
  /// are theirs put together with region = solid number (1, 2, ...), `labels` theirs (triangles
  /// of solid 1 first), `quality` and `generated_quality` measured on those; `method` Overlay when
  /// every solid's mesh is an overlay mesh, else Polycube; level, edge_weight, frame, stretch and the
  /// polycube options are the first solid's; `polycube` is empty. Empty for one solid.
  std::vector<MeshSurfaceRun> solids;
  /// Of those, the pairs (1-based, first < second) that touch (mesh::SurfaceCheck::touching): their
  /// meshes do not conform where they meet.
  std::vector<std::array<int, 2>> touching;
  /// Order 2: how the mid-edge nodes were placed (`mesh` and `quality` are the second-order mesh's).
  optimize::SecondOrderReport second_order;
  /// With local sizes (options.overlay.local_sizes): how the mesh meets them, measured on the path's
  /// mesh before any snap; empty otherwise. Method::Auto prefers the path that meets more of them.
  LocalSizeFit local_fit;
};

/// InputError for an element order other than 1 or 2.
void check_order(int order);

/// InputError for a negative min_size or max_size, min_size > max_size (both > 0), or a growth
/// rate (overlay.growth_rate) not in (1, 3].
void check_size_bounds(const MeshSurfaceOptions& options);

/// `size` (> 0) within [options.min_size, options.max_size], each bound when > 0; checks them first
/// (check_size_bounds).
double bounded_size(double size, const MeshSurfaceOptions& options);

/// The element size mesh_surface meshes `surface` with: options.size, or its default (the diagonal
/// of the surface's box, square to the frame its faces fit when options.align, over 30), within the
/// bounds (bounded_size).
double element_size(const mesh::SurfaceMesh& surface, const MeshSurfaceOptions& options);

/// Runs the path options.method names (see Method); for the polycube, segment -> autopolycube ->
/// generate -> improve on `surface` (closed, oriented outward; its patch ids are CAD faces when there
/// are several, see CvtOptions::respect_faces). With check_input, a surface bounding several solids
/// has each solid meshed on its own (see MeshSurfaceRun::solids); when one fails, the error is
/// thrown with `progress` holding that solid's run. When `progress`
/// is given it holds, also when this throws, what the finished stages produced. Inverted cells that
/// remain are reported in `quality`, not thrown. Throws what the stages throw; with Method::Polycube
/// and a deadline (see polycube_seconds) TimeoutError when it passes before a mesh exists;
/// InterruptedError, within a fraction of a second, once the calling thread's interrupt is raised
/// (common/interrupt.h; both paths under auto stop); TimeoutError past options.time_limit.
MeshSurfaceRun mesh_surface(const mesh::SurfaceMesh& surface, const MeshSurfaceOptions& options = {},
                            MeshSurfaceRun* progress = nullptr);

/// The polycube path's last stages on a polycube structure (its blocks `structure` on the patch
/// surface `patches`, made by autopolycube or built by hand), as mesh_surface runs them on the
/// structure it made: generate (opt.level, relax_sweeps, threads), then with opt.improve the
/// improvement (opt.improvement with `patches` as the surface, target_edge_ratio, deadline: it
/// stops early with its best so far). Sets r.generated, generated_quality, mesh, quality,
/// seconds[2..3], level, budget_passed and stage ("done"; "generate" or "improve" when it throws).
/// With `local` (the local sizes' field over the surface meshed), the generated mesh is refined
/// by thirds where it asks for smaller cells before the improvement (refine_to_local_sizes,
/// local_refinement.h). Logs one line per stage to opt.log.
void generate_and_improve(const mesh::SurfaceMesh& patches, const mesh::Mesh& structure, const MeshSurfaceOptions& opt,
                          MeshSurfaceRun& r, const overlay::LocalSizeField* local = nullptr);

/// The solids' runs `runs` (each made by mesh_surface on one solid) as one run (see
/// MeshSurfaceRun::solids), moved into `r`.
void merge_solid_runs(std::vector<MeshSurfaceRun> runs, MeshSurfaceRun& r);

/// Copies the stages of the polycube path's run `attempt` (labels, polycube and the options that
/// rebuild them; see MeshSurfaceRun) into the overlay's run `overlay`.
void keep_polycube_attempt(const MeshSurfaceRun& attempt, MeshSurfaceRun& overlay);

/// The snap's SnapOptions::face_only for the mesh of `run`: for an overlay mesh, its nodes put on a
/// smooth region (OverlayResult::node_kind Surface; some were let off a sharp curve on purpose, and
/// putting them back on it flattens their cells); empty for a polycube mesh. The CLI's snap and the
/// workbench's (through _hexdom) both take it from here.
std::vector<char> snap_face_only(const MeshSurfaceRun& run);

/// The polycube path's deadline for a call starting now: options.deadline when set; otherwise in
/// Method::Auto polycube_seconds from now (none for 0); none for Polycube and Overlay.
Deadline polycube_deadline(const MeshSurfaceOptions& options);

/// polycube_note's text for an error of the polycube path that stopped at `stage`: "the polycube
/// path stopped after its time budget of 5 s at stage autopolycube" for a TimeoutError, "the
/// polycube path failed at stage autopolycube: <first line of the error>" for the others.
std::string polycube_failure_note(const Error& error, const std::string& stage);

/// Whether run b is better than run a by the candidates' order (see try_without_widths): fewer
/// inverted cells, then a worst SJ >= target_sj, then a volume within target_volume of `reference`,
/// then more of the local sizes met (local_fit; runs measured alike: both with them or both without),
/// then a largest edge ratio within target_edge_ratio (when both miss it and meet target_sj: the
/// smaller largest edge ratio), then the higher worst SJ.
bool better_run(const MeshSurfaceRun& b, const MeshSurfaceRun& a, double reference, const MeshSurfaceOptions& options);

/// Whether a run meets every target: no inverted cell, worst SJ >= target_sj, volume within
/// target_volume of `reference`.
bool meets_targets(const MeshSurfaceRun& r, double reference, const MeshSurfaceOptions& options);
/// meets_targets, a largest edge ratio within target_edge_ratio and every local size met (local_fit):
/// the test after which Method::Auto keeps the polycube mesh without running the overlay path.
bool meets_path_targets(const MeshSurfaceRun& r, double reference, const MeshSurfaceOptions& options);

/// "level 1: worst SJ 0.190, 0 inverted, volume -1.18%" (the overlay's: "overlay: ..."), for the
/// lines that say why another candidate is tried.
std::string run_summary(const MeshSurfaceRun& r, double reference);

/// "segment: 12 charts in 0.21 s"-style summary of a run, one line per finished stage, then the
/// kept candidate's options (choice_text).
std::string to_text(const MeshSurfaceRun& run);

/// "worst hex SJ 0.620, prism 0.400, 2 inverted": each cell type's worst, then the inverted cells.
std::string worst_by_type(const quality::QualityReport& q);

/// "second order: 1200 boundary mid-edge nodes (80 on CAD edges, 1120 on faces), moved up to 0.05
/// off their edges; 1190 placed, 6 halfway or less, 4 kept straight; worst SJ 0.4, 0 inverted".
std::string second_order_text(const optimize::SecondOrderReport& report);

/// The options of the kept candidate on one line: "level 1, lambda 0.1, widths of holes kept, tet
/// blocks at apexes" (the last part only when the polycube has apex caps).
std::string choice_text(const MeshSurfaceRun& run);

}  // namespace hexdom::pipeline
