#include "hexdom/cad/mesh_cad.h"

#include <algorithm>
#include <chrono>
#include <exception>

#include "hexdom/common/format.h"

namespace hexdom::cad {

namespace {
int inverted_cells(const quality::QualityReport& q) { return q.hex.inverted + q.prism.inverted + q.tet.inverted; }

// mesh_surface of r.surface, then the snap onto the B-rep (r.run's mesh and quality replaced).
void mesh_and_snap(const Shape& shape, const autopolycube::MeshSurfaceOptions& mo, const MeshCadOptions& opt, MeshCadRun& r) {
  autopolycube::mesh_surface(r.surface, mo, &r.run);
  if (!opt.snap) return;
  const auto t0 = std::chrono::steady_clock::now();
  SnapResult sr = snap_to_brep(shape, r.run.mesh, r.surface, opt.snap_options);
  r.run.mesh = std::move(sr.mesh);
  r.run.quality = sr.quality;
  r.snap = std::move(sr);
  r.snap.mesh = mesh::Mesh{};
  r.snapped = true;
  r.snap_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}
}  // namespace

MeshCadRun mesh_cad_part(const Shape& shape, const MeshCadOptions& opt, MeshCadRun* progress) {
  MeshCadRun local;
  MeshCadRun& r = progress ? *progress : local;
  r = MeshCadRun{};
  auto say = [&](const std::string& m) { if (opt.log) opt.log(0, m); };
  r.surface = tessellate(shape, opt.tessellation, &r.stats);
  r.tessellations = 1;
  const double reference = r.stats.brep_volume != 0 ? r.stats.brep_volume : mesh::enclosed_volume(r.surface.V, r.surface.F);
  std::exception_ptr first_error;
  try {
    mesh_and_snap(shape, opt.mesh, opt, r);
  } catch (const GeometryError&) {
    first_error = std::current_exception();
  } catch (const MeshingError&) {
    first_error = std::current_exception();
  }
  bool meshed = !first_error;
  if (meshed && inverted_cells(r.run.quality) == 0) return r;
  // Later tessellations: the same grid (the first surface's element size), other triangles.
  autopolycube::MeshSurfaceOptions mo = opt.mesh;
  mo.size = autopolycube::default_size(r.surface, opt.mesh);
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
    TessellateOptions to = opt.tessellation;
    to.size = f * first_size;
    MeshCadRun again;
    again.tessellation_factor = f;
    again.surface = tessellate(shape, to, &again.stats);
    ++r.tessellations;
    try {
      mesh_and_snap(shape, mo, opt, again);
    } catch (const GeometryError& e) {
      say(fmt("tessellation at %.2f x the size: ", f) + std::string(e.what()).substr(0, std::string(e.what()).find('\n')));
      continue;
    } catch (const MeshingError& e) {
      say(fmt("tessellation at %.2f x the size: ", f) + std::string(e.what()).substr(0, std::string(e.what()).find('\n')));
      continue;
    }
    if (!meshed || autopolycube::better_run(again.run, r.run, reference, mo)) {
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

}  // namespace hexdom::cad
