#include "hexdom/pipeline/mesh_cad.h"

#include <algorithm>
#include <chrono>
#include <exception>

#include "hexdom/common/format.h"
#include "hexdom/segmentation/cube_frame.h"

namespace hexdom::pipeline {

namespace {
int inverted_cells(const quality::QualityReport& q) { return q.hex.inverted + q.prism.inverted + q.tet.inverted; }

// mesh_surface of r.surface, then the snap onto the B-rep (r.run's mesh and quality replaced).
void mesh_and_snap(const cad::Shape& shape, const MeshSurfaceOptions& mo, const MeshCadOptions& opt, MeshCadRun& r) {
  pipeline::mesh_surface(r.surface, mo, &r.run);
  if (!opt.snap) return;
  const auto t0 = std::chrono::steady_clock::now();
  cad::SnapResult sr = cad::snap_to_brep(shape, r.run.mesh, r.surface, opt.snap_options);
  r.run.mesh = std::move(sr.mesh);
  r.run.quality = sr.quality;
  r.snap = std::move(sr);
  r.snap.mesh = mesh::Mesh{};
  r.snapped = true;
  r.snap_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}
}  // namespace

MeshCadRun mesh_cad_part(const cad::Shape& shape, const MeshCadOptions& opt, MeshCadRun* progress) {
  MeshCadRun local;
  MeshCadRun& r = progress ? *progress : local;
  r = MeshCadRun{};
  auto say = [&](const std::string& m) { if (opt.log) opt.log(0, m); };
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
      mesh_and_snap(shape, mo, opt, run);
      return true;
    } catch (const GeometryError& e) {
      return defeated(e);
    } catch (const MeshingError& e) {
      return defeated(e);
    }
  };
  r.surface = cad::tessellate(shape, opt.tessellation, &r.stats);
  r.tessellations = 1;
  say(fmt("tessellate: %.0f triangles on %.0f CAD faces in %.2f s", r.stats.triangles, r.stats.faces, r.stats.seconds));
  const double reference = r.stats.brep_volume != 0 ? r.stats.brep_volume : mesh::enclosed_volume(r.surface.V, r.surface.F);
  std::exception_ptr first_error;
  bool meshed = attempt(opt.mesh, r, &first_error);
  if (meshed && inverted_cells(r.run.quality) == 0) return r;
  // The overlay grid hardly depends on the triangles: another tessellation would give the same mesh.
  if (meshed && r.run.method == Method::Overlay) return r;
  // Later tessellations: the same grid (the element size the first run took, in its frame), other
  // triangles.
  MeshSurfaceOptions mo = opt.mesh;
  if (mo.size <= 0) mo.size = segmentation::frame_diagonal(r.surface, r.run.frame.rotation) / 30.0;
  const double first_size = r.stats.size;
  const std::string why = meshed ? fmt(r.snapped ? "%.0f inverted cells after the snap" : "%.0f inverted cells remain",
                                       inverted_cells(r.run.quality))
                                 : "the automatic polycube failed at stage " + r.run.stage;
  const size_t tries = meshed ? std::min(opt.retessellate.size(), static_cast<size_t>(std::max(0, opt.retessellate_inverted)))
                               : opt.retessellate.size();
  for (size_t k = 0; k < tries; ++k) {
    const double f = opt.retessellate[k];
    say(why + ": tessellating again with triangles of " + fmt("%.2f", f) + " x the size (" + fmt("%g", f * first_size) +
        "), the polycube grid kept at " + fmt("%g", mo.size));
    cad::TessellateOptions to = opt.tessellation;
    to.size = f * first_size;
    MeshCadRun again;
    again.tessellation_factor = f;
    again.surface = cad::tessellate(shape, to, &again.stats);
    ++r.tessellations;
    if (!attempt(mo, again, nullptr)) continue;
    if (!meshed || pipeline::better_run(again.run, r.run, reference, mo)) {
      const int tessellations = r.tessellations;
      r = std::move(again);
      r.tessellations = tessellations;
      meshed = true;
      say(fmt("kept the tessellation at %.2f x the size", f));
    }
    if (inverted_cells(r.run.quality) == 0) break;
  }
  if (!meshed) std::rethrow_exception(first_error);
  return r;
}

}  // namespace hexdom::pipeline
