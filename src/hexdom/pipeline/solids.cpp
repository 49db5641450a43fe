// Several solids in one surface: their runs put together as one (see MeshSurfaceRun::solids).
#include <algorithm>
#include <utility>

#include "hexdom/pipeline/mesh_surface.h"
#include "hexdom/quality/report.h"

namespace hexdom::pipeline {

namespace {

// The runs' meshes (`member`: generated or mesh) as one mesh, the cells of solid k in region k + 1;
// second order when every one is.
mesh::Mesh put_together(const std::vector<MeshSurfaceRun>& runs, mesh::Mesh MeshSurfaceRun::*member) {
  Eigen::Index nv = 0, nc = 0;
  bool second = !runs.empty();
  for (const MeshSurfaceRun& r : runs) {
    nv += (r.*member).V.rows();
    nc += (r.*member).cells.rows();
    second = second && (r.*member).second_order();
  }
  mesh::Mesh m;
  m.V.resize(nv, 3);
  m.cells.resize(nc, 8);
  m.types.resize(nc);
  m.region.resize(nc);
  if (second) m.mid.resize(nc, 12);
  Eigen::Index v0 = 0, c0 = 0;
  for (size_t k = 0; k < runs.size(); ++k) {
    const mesh::Mesh& p = runs[k].*member;
    m.V.middleRows(v0, p.V.rows()) = p.V;
    for (Eigen::Index c = 0; c < p.cells.rows(); ++c)
      for (int j = 0; j < 8; ++j) m.cells(c0 + c, j) = p.cells(c, j) < 0 ? -1 : p.cells(c, j) + static_cast<int>(v0);
    if (second)
      for (Eigen::Index c = 0; c < p.cells.rows(); ++c)
        for (int e = 0; e < 12; ++e) m.mid(c0 + c, e) = p.mid(c, e) < 0 ? -1 : p.mid(c, e) + static_cast<int>(v0);
    m.types.segment(c0, p.types.size()) = p.types;
    m.region.segment(c0, p.types.size()).setConstant(static_cast<int>(k) + 1);
    v0 += p.V.rows();
    c0 += p.cells.rows();
  }
  return m;
}

}  // namespace

void merge_solid_runs(std::vector<MeshSurfaceRun> runs, MeshSurfaceRun& r) {
  r = MeshSurfaceRun{};
  if (runs.empty()) return;
  const MeshSurfaceRun& first = runs.front();
  r.method = std::all_of(runs.begin(), runs.end(), [](const MeshSurfaceRun& s) { return s.method == Method::Overlay; })
                 ? Method::Overlay
                 : Method::Polycube;
  r.mesh = put_together(runs, &MeshSurfaceRun::mesh);
  r.generated = put_together(runs, &MeshSurfaceRun::generated);
  std::vector<const mesh::SurfaceMesh*> labels;
  for (const MeshSurfaceRun& s : runs) labels.push_back(&s.labels);
  r.labels = mesh::join_surfaces(labels);
  r.quality = quality::quality_report(r.mesh);
  r.generated_quality = quality::quality_report(r.generated);
  r.edge_weight = first.edge_weight;
  r.level = first.level;
  r.keep_widths = first.keep_widths;
  r.collapse_apexes = first.collapse_apexes;
  r.frame = first.frame;
  r.stretch = first.stretch;
  for (size_t k = 0; k < runs.size(); ++k) {
    const MeshSurfaceRun& s = runs[k];
    for (int i = 0; i < 4; ++i) r.seconds[i] += s.seconds[i];
    r.segmentations += s.segmentations;
    r.surface_volume += s.surface_volume;
    r.budget_passed = r.budget_passed || s.budget_passed;
    r.polycube_meshed = r.polycube_meshed || s.polycube_meshed;
    if (!s.polycube_note.empty())
      r.polycube_note += (r.polycube_note.empty() ? "" : "; ") + ("solid " + std::to_string(k + 1) + ": " + s.polycube_note);
  }
  r.stage = "done";
  r.solids = std::move(runs);
}

}  // namespace hexdom::pipeline
