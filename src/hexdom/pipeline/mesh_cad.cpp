#include "hexdom/pipeline/mesh_cad.h"

#include <algorithm>
#include <cmath>
#include <chrono>
#include <exception>
#include <map>
#include <string>
#include <vector>

#include "hexdom/cad/project.h"
#include "hexdom/cad/read_shape.h"
#include "hexdom/cad/second_order.h"
#include "hexdom/common/format.h"
#include "hexdom/common/interrupt.h"
#include "hexdom/common/stopwatch.h"
#include "hexdom/common/time_limit.h"
#include "hexdom/mesh/surface_check.h"
#include "hexdom/pipeline/choice.h"
#include "hexdom/segmentation/cube_frame.h"

namespace hexdom::pipeline {

namespace {
using quality::inverted_cells;

// mesh_surface of r.surface with one path, then the snap onto the B-rep (r.run's mesh and quality
// replaced).
void mesh_path_and_snap(const cad::Shape& shape, const MeshSurfaceOptions& mo, const MeshCadOptions& opt, MeshCadRun& r) {
  pipeline::mesh_surface(r.surface, mo, &r.run);
  if (!opt.snap) return;
  if (mo.deadline.cancelled()) mo.deadline.check("snap");  // called off (auto's overlay beside the polycube)
  const auto t0 = std::chrono::steady_clock::now();
  cad::SnapOptions so = opt.snap_options;
  so.max_edge_ratio = mo.target_edge_ratio;
  so.threads = mo.threads;
  if (so.log && mo.log) so.log = mo.log;  // the run's own sink (choose_path keeps the overlay's messages)
  // The overlay's nodes on smooth regions stay off the CAD edges (snap_face_only).
  if (so.face_only.empty()) so.face_only = snap_face_only(r.run);
  cad::SnapResult sr = cad::snap_to_brep(shape, r.run.mesh, r.surface, so);
  r.unsnapped_mesh = std::move(r.run.mesh);
  r.unsnapped_quality = r.run.quality;
  r.run.mesh = std::move(sr.mesh);
  r.run.quality = sr.quality;
  r.snap = std::move(sr);
  r.snap.mesh = mesh::Mesh{};
  r.snapped = true;
  r.snap_seconds = seconds_since(t0);
}

// mesh_path_and_snap with mo's method; Auto: choose_path (choice.h) between the snapped meshes of
// the two paths, measured against `reference`, the B-rep's volume.
void mesh_and_snap(const cad::Shape& shape, const MeshSurfaceOptions& mo, const MeshCadOptions& opt, double reference,
                   MeshCadRun& r) {
  if (mo.method != Method::Auto) return mesh_path_and_snap(shape, mo, opt, r);
  choose_path(
      mo, reference, [&](const MeshSurfaceOptions& o, MeshCadRun& run) { mesh_path_and_snap(shape, o, opt, run); },
      [](MeshCadRun& run) -> MeshSurfaceRun& { return run.run; },
      [](const MeshCadRun& like) {
        MeshCadRun other;
        other.surface = like.surface;
        other.stats = like.stats;
        other.tessellation_factor = like.tessellation_factor;
        other.tessellations = like.tessellations;
        return other;
      },
      [](const MeshCadRun& run) {
        MeshSurfaceRun u = run.run;
        if (run.snapped) {
          u.mesh = run.unsnapped_mesh;
          u.quality = run.unsnapped_quality;
        }
        return u;
      },
      r);
}

MeshCadRun mesh_cad_first_order(const cad::Shape& shape, const MeshCadOptions& opt, MeshCadRun* progress);

// mesh_cad_part in the shape's own numbers (Face1..Face<n> of the solid).
MeshCadRun mesh_cad_own(const cad::Shape& shape, const MeshCadOptions& opt, MeshCadRun* progress) {
  check_order(opt.mesh.order);
  if (opt.mesh.order == 1) return mesh_cad_first_order(shape, opt, progress);
  MeshCadOptions first = opt;
  first.mesh.order = 1;
  MeshCadRun local;
  MeshCadRun& r = progress ? *progress : local;
  mesh_cad_first_order(shape, first, &r);
  r.run.stage = "second order";
  if (r.snapped) {
    cad::SecondOrderResult s = cad::second_order_on_brep(shape, r.run.mesh, r.snap.kind, r.snap.entity, r.surface, opt.mesh.curve);
    r.run.mesh = std::move(s.mesh);
    r.run.quality = std::move(s.quality);
    r.run.second_order = s.report;
  } else {
    r.run.mesh = optimize::second_order_on_surface(r.run.mesh, r.surface, opt.mesh.curve, &r.run.second_order);
    r.run.quality = quality::quality_report(r.run.mesh);
  }
  if (opt.log) opt.log(0, second_order_text(r.run.second_order));
  check_interrupt("mesh");
  r.run.stage = "done";
  return r;
}

// The solid's own number of each of the source's numbers of its faces (dim 2) or edges (dim 1).
std::map<int, int> own_numbers(const std::vector<int>& source) {
  std::map<int, int> own;
  for (size_t i = 0; i < source.size(); ++i) own[source[i]] = static_cast<int>(i) + 1;
  return own;
}

// "Face7, Face8, Face9" (at most 8 named, then a count).
std::string entity_list(const char* kind, const std::vector<int>& source) {
  std::string out;
  for (size_t i = 0; i < source.size() && i < 8; ++i) out += (i ? ", " : "") + std::string(kind) + std::to_string(source[i]);
  if (source.size() > 8) out += " and " + std::to_string(source.size() - 8) + " more";
  return out;
}

// `opt` with its local sizes on faces and edges, given in the source's numbers, in the solid's own;
// InputError for a number that is not one of the solid's.
MeshCadOptions in_own_numbers(const MeshCadOptions& opt, const std::vector<int>& faces, const std::vector<int>& edges) {
  MeshCadOptions o = opt;
  const std::map<int, int> face = own_numbers(faces), edge = own_numbers(edges);
  for (overlay::LocalSize& l : o.mesh.overlay.local_sizes) {
    if (l.patch <= 0 || l.polyline.rows() > 0) continue;
    auto it = face.find(l.patch);
    if (it == face.end())
      throw InputError("a local size is given on Face" + std::to_string(l.patch) + ", which is not a face of the solid meshed (" +
                       entity_list("Face", faces) + ")");
    l.patch = it->second;
  }
  for (auto& [number, size] : o.edge_sizes) {
    auto it = edge.find(number);
    if (it == edge.end())
      throw InputError("a local size is given on Edge" + std::to_string(number) + ", which is not an edge of the solid meshed (" +
                       entity_list("Edge", edges) + ")");
    number = it->second;
  }
  return o;
}

// r's tessellation patches, snapped entities and node faces in the source's numbers.
void to_source_numbers(const cad::Shape& shape, MeshCadRun& r) {
  const std::vector<int> numbers[4] = {{}, cad::source_numbers(shape, 2), cad::source_numbers(shape, 1),
                                       cad::source_numbers(shape, 0)};
  auto map = [](const std::vector<int>& n, int own) { return own >= 1 && own <= static_cast<int>(n.size()) ? n[own - 1] : 0; };
  for (Eigen::Index t = 0; t < r.surface.patch.size(); ++t) r.surface.patch(t) = map(numbers[1], r.surface.patch(t));
  for (size_t v = 0; v < r.snap.entity.size() && v < r.snap.kind.size(); ++v)
    r.snap.entity[v] = map(numbers[static_cast<int>(r.snap.kind[v])], r.snap.entity[v]);
  for (std::vector<int>& faces : r.snap.faces) {
    for (int& f : faces) f = map(numbers[1], f);
    std::sort(faces.begin(), faces.end());
  }
}

}  // namespace

MeshCadRun mesh_cad_part(const cad::Shape& shape, const MeshCadOptions& opt, MeshCadRun* progress) {
  if (opt.mesh.time_limit > 0) {
    MeshCadOptions inner = opt;
    inner.mesh.time_limit = 0;
    MeshCadRun local;
    MeshCadRun& r = progress ? *progress : local;
    run_with_time_limit(opt.mesh.time_limit, [&] { mesh_cad_part(shape, inner, &r); });
    return r;
  }
  const std::vector<int> faces = cad::source_numbers(shape, 2);
  bool own = true;
  for (int dim = 0; dim < 3 && own; ++dim) {
    const std::vector<int> n = dim == 2 ? faces : cad::source_numbers(shape, dim);
    for (size_t i = 0; i < n.size() && own; ++i) own = n[i] == static_cast<int>(i) + 1;
  }
  if (own) return mesh_cad_own(shape, opt, progress);
  MeshCadRun local;
  MeshCadRun& r = progress ? *progress : local;
  mesh_cad_own(shape, in_own_numbers(opt, faces, cad::source_numbers(shape, 1)), &r);
  to_source_numbers(shape, r);
  return r;
}

namespace {

MeshCadRun mesh_cad_first_order(const cad::Shape& shape, const MeshCadOptions& opt, MeshCadRun* progress) {
  MeshCadRun local;
  MeshCadRun& r = progress ? *progress : local;
  r = MeshCadRun{};
  auto say = [&](const std::string& m) { if (opt.log) opt.log(0, m); };
  // Local sizes along edges: polylines among the local sizes.
  if (!opt.edge_sizes.empty()) {
    MeshCadOptions o = opt;
    o.edge_sizes.clear();
    for (const auto& [edge, size] : opt.edge_sizes) {
      if (!(size > 0) || !std::isfinite(size))
        throw InputError(fmt("local size %g on Edge", size) + fmt("%.0f: a size must be positive", double(edge)));
      overlay::LocalSize l;
      l.size = size;
      l.polyline = cad::edge_points(shape, edge, size / 4);
      o.mesh.overlay.local_sizes.push_back(std::move(l));
    }
    return mesh_cad_first_order(shape, o, progress);
  }
  double reference = 0;  // the B-rep's volume, once tessellated
  // mesh_and_snap of `run`, true when it gave a mesh; what defeated it (a labelling the repair
  // cannot use, a failed cut) is said when `why` is given, or kept in `error`.
  auto attempt = [&](const MeshSurfaceOptions& mo, MeshCadRun& run, std::exception_ptr* error) {
    auto defeated = [&](const Error& e) {
      if (error) *error = std::current_exception();
      else say(fmt("tessellation at %.2f x the size: ", run.tessellation_factor) +
               std::string(e.what()).substr(0, std::string(e.what()).find('\n')));
      return false;
    };
    try {
      // Each tessellation checked once (mo.check_input is off for the paths' runs on it).
      if (opt.mesh.check_input)
        for (const std::string& w : mesh::check_solid_surface(run.surface, opt.mesh.input_name).warnings)
          if (opt.log) opt.log(1, w);
      mesh_and_snap(shape, mo, opt, reference, run);
      return true;
    } catch (const GeometryError& e) {
      return defeated(e);
    } catch (const MeshingError& e) {
      return defeated(e);
    }
  };
  // With bounds on the element size, the triangles take the bounded size too (a default size
  // beyond a bound: tessellated again with the bound), and the paths mesh with it.
  const bool bounded = opt.mesh.max_size != 0 || opt.mesh.min_size != 0;
  cad::TessellateOptions to = opt.tessellation;
  if (bounded && to.size > 0) to.size = bounded_size(to.size, opt.mesh);
  r.surface = cad::tessellate(shape, to, &r.stats);
  if (bounded && bounded_size(r.stats.size, opt.mesh) != r.stats.size) {
    to.size = bounded_size(r.stats.size, opt.mesh);
    say(fmt("tessellate: size %g, within the min and max size: %g", r.stats.size, to.size));
    const double seconds = r.stats.seconds;
    r.surface = cad::tessellate(shape, to, &r.stats);
    r.stats.seconds += seconds;
  }
  r.tessellations = 1;
  say(fmt("tessellate: %.0f triangles on %.0f CAD faces in %.2f s", r.stats.triangles, r.stats.faces, r.stats.seconds));
  overlay::check_local_sizes(opt.mesh.overlay.local_sizes, r.surface, "the part");  // each face asked for is one of the part's
  reference = r.stats.brep_volume != 0 ? r.stats.brep_volume : mesh::enclosed_volume(r.surface.V, r.surface.F);
  // One time budget for the polycube path over every tessellation of this call, from here: the first
  // tessellation serves both paths (on a part with many small faces it alone can take longer than
  // the budget), the later ones are made for the polycube and count.
  MeshSurfaceOptions first = opt.mesh;
  if (bounded && first.size <= 0) first.size = bounded_size(r.stats.size, opt.mesh);  // as the triangles'
  first.deadline = polycube_deadline(opt.mesh);
  first.check_input = false;  // done once per tessellation by `attempt`
  std::exception_ptr first_error;
  bool meshed = attempt(first, r, &first_error);  // a TimeoutError here (Method::Polycube) is passed on
  // Done when the mesh has no inverted cell, or in auto mode when the overlay's mesh was kept.
  auto done = [&] {
    // Auto: once the overlay's mesh is kept, another tessellation is not tried for a polycube (on
    // the corpus it gave a better mesh for 0 of 23 parts, 11 whose polycube had meshed and 12 whose
    // labelling had defeated the repair, and cost up to the polycube path's whole budget).
    if (opt.mesh.method == Method::Auto && r.run.method == Method::Overlay) return true;
    return inverted_cells(r.run.quality) == 0;
  };
  if (meshed && done()) return r;
  // With the overlay path alone no other tessellation is tried: the grid is the same, and its
  // outcome on other triangles is no better on the whole.
  if (meshed && opt.mesh.method == Method::Overlay) return r;
  // Later tessellations: the same grid (the element size the first run took, in its frame), other
  // triangles.
  MeshSurfaceOptions mo = first;
  if (mo.size <= 0) mo.size = segmentation::frame_diagonal(r.surface, r.run.frame.rotation) / 30.0;
  const double first_size = r.stats.size;
  const std::string why = !meshed ? "the automatic polycube failed at stage " + r.run.stage
                                   : fmt(r.snapped ? "%.0f inverted cells after the snap" : "%.0f inverted cells remain",
                                         inverted_cells(r.run.quality));
  const size_t tries = meshed ? std::min(opt.retessellate.size(), static_cast<size_t>(std::max(0, opt.retessellate_inverted)))
                              : opt.retessellate.size();
  for (size_t k = 0; k < tries; ++k) {
    const double f = opt.retessellate[k];
    if (mo.method != Method::Overlay && mo.deadline.passed()) {
      say(why + fmt(": no further tessellation, the polycube path's time budget of %g s has passed", mo.deadline.budget()));
      break;
    }
    say(why + ": tessellating again with triangles of " + fmt("%.2f", f) + " x the size (" + fmt("%g", f * first_size) +
        "), the polycube grid kept at " + fmt("%g", mo.size));
    to.size = f * first_size;
    MeshCadRun again;
    again.tessellation_factor = f;
    again.surface = cad::tessellate(shape, to, &again.stats);
    ++r.tessellations;
    try {
      if (!attempt(mo, again, nullptr)) continue;
    } catch (const TimeoutError& e) {  // the run so far is kept
      say(fmt("tessellation at %.2f x the size: ", f) + e.what() + "; no further tessellation");
      break;
    }
    if (!meshed || pipeline::better_run(again.run, r.run, reference, mo)) {
      const int tessellations = r.tessellations;
      r = std::move(again);
      r.tessellations = tessellations;
      meshed = true;
      say(fmt("kept the tessellation at %.2f x the size", f));
    }
    if (done()) break;
  }
  if (!meshed) std::rethrow_exception(first_error);
  check_interrupt("mesh");  // interrupted after the stages' last look: no result
  return r;
}

}  // namespace

}  // namespace hexdom::pipeline
