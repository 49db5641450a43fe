// Every solid of a CAD file meshed, and their runs put together as one part (mesh_cad_solids).
#include <algorithm>
#include <set>
#include <string>

#include "hexdom/cad/read_shape.h"
#include "hexdom/common/time_limit.h"
#include "hexdom/pipeline/mesh_cad.h"

namespace hexdom::pipeline {

namespace {

// `opt` for one solid: the sizes on faces and edges of other solids left out (all in the source's
// numbers, which mesh_cad_part takes).
MeshCadOptions options_of_solid(const MeshCadOptions& opt, const cad::Shape& solid) {
  MeshCadOptions one = opt;
  const std::vector<int> faces = cad::source_numbers(solid, 2), edges = cad::source_numbers(solid, 1);
  auto has = [](const std::vector<int>& v, int n) { return std::find(v.begin(), v.end(), n) != v.end(); };
  one.mesh.overlay.local_sizes.clear();
  for (const overlay::LocalSize& l : opt.mesh.overlay.local_sizes)
    if (l.patch <= 0 || l.polyline.rows() > 0 || has(faces, l.patch)) one.mesh.overlay.local_sizes.push_back(l);
  one.edge_sizes.clear();
  for (const auto& [edge, size] : opt.edge_sizes)
    if (has(edges, edge)) one.edge_sizes.emplace_back(edge, size);
  return one;
}

// Every face and edge a size is given on belongs to one of the solids.
void check_size_numbers(const std::vector<cad::Shape>& solids, const MeshCadOptions& opt) {
  std::set<int> faces, edges;
  for (const cad::Shape& s : solids) {
    for (int n : cad::source_numbers(s, 2)) faces.insert(n);
    for (int n : cad::source_numbers(s, 1)) edges.insert(n);
  }
  for (const overlay::LocalSize& l : opt.mesh.overlay.local_sizes)
    if (l.patch > 0 && l.polyline.rows() == 0 && !faces.count(l.patch))
      throw InputError("a local size is given on Face" + std::to_string(l.patch) + ", but the part's solids have " +
                       std::to_string(faces.size()) + " faces");
  for (const auto& [edge, size] : opt.edge_sizes)
    if (!edges.count(edge))
      throw InputError("a local size is given on Edge" + std::to_string(edge) + ", but the part's solids have " +
                       std::to_string(edges.size()) + " edges");
}

// The solids' snaps as one: node kinds, entities and faces in the merged mesh's node order, counts summed,
// the largest distances and moves, the worst cells, means over all boundary nodes. Its mesh and
// quality are left empty (they are the part's run.mesh and quality).
cad::SnapResult snaps_together(const std::vector<MeshCadRun>& runs) {
  cad::SnapResult out;
  cad::SnapReport& t = out.report;
  bool first = true;
  for (size_t k = 0; k < runs.size(); ++k) {
    const cad::SnapResult& s = runs[k].snap;
    const cad::SnapReport& q = s.report;
    out.kind.insert(out.kind.end(), s.kind.begin(), s.kind.end());
    out.entity.insert(out.entity.end(), s.entity.begin(), s.entity.end());
    out.entity.resize(out.kind.size(), 0);
    // A second-order mesh's mid-edge nodes follow its corners: none has a kind of its own.
    out.kind.resize(out.kind.size() + std::max<Eigen::Index>(0, runs[k].run.mesh.V.rows() - static_cast<Eigen::Index>(s.kind.size())),
                    cad::SnapKind::Interior);
    out.entity.resize(out.kind.size(), 0);
    out.faces.insert(out.faces.end(), s.faces.begin(), s.faces.end());
    out.faces.resize(out.kind.size());
    const double before = t.boundary_nodes + q.boundary_nodes;
    if (before > 0) {
      t.mean_before = (t.mean_before * t.boundary_nodes + q.mean_before * q.boundary_nodes) / before;
      t.mean_after = (t.mean_after * t.boundary_nodes + q.mean_after * q.boundary_nodes) / before;
    }
    t.boundary_nodes += q.boundary_nodes;
    t.face_nodes += q.face_nodes;
    t.edge_nodes += q.edge_nodes;
    t.vertex_nodes += q.vertex_nodes;
    t.max_before = std::max(t.max_before, q.max_before);
    t.max_after = std::max(t.max_after, q.max_after);
    t.max_move = std::max(t.max_move, q.max_move);
    t.diagonal = std::max(t.diagonal, q.diagonal);
    t.inverted_snapped += q.inverted_snapped;
    t.inverted += q.inverted;
    t.worst_sj_before = first ? q.worst_sj_before : std::min(t.worst_sj_before, q.worst_sj_before);
    t.worst_sj_snapped = first ? q.worst_sj_snapped : std::min(t.worst_sj_snapped, q.worst_sj_snapped);
    t.worst_sj = first ? q.worst_sj : std::min(t.worst_sj, q.worst_sj);
    t.seconds_project += q.seconds_project;
    t.seconds_restore += q.seconds_restore;
    first = false;
  }
  return out;
}

// The solids' runs as one part's (MeshSolidsRun::part).
void put_part_together(std::vector<MeshCadRun>& runs, MeshCadRun& part) {
  part = MeshCadRun{};
  std::vector<const mesh::SurfaceMesh*> surfaces;
  for (const MeshCadRun& r : runs) surfaces.push_back(&r.surface);
  part.surface = mesh::join_surfaces(surfaces);
  part.snapped = !runs.empty() && std::all_of(runs.begin(), runs.end(), [](const MeshCadRun& r) { return r.snapped; });
  if (part.snapped) part.snap = snaps_together(runs);
  part.stats = runs.front().stats;
  part.tessellation_factor = runs.front().tessellation_factor;
  for (size_t k = 1; k < runs.size(); ++k) {
    const cad::TessellateStats& s = runs[k].stats;
    cad::TessellateStats& t = part.stats;
    t.triangles += s.triangles, t.vertices += s.vertices, t.faces += s.faces;
    t.min_angle = std::min(t.min_angle, s.min_angle);
    t.min_angle_planar = std::min(t.min_angle_planar, s.min_angle_planar);
    t.mean_edge = (t.mean_edge * (t.triangles - s.triangles) + s.mean_edge * s.triangles) / std::max(1, t.triangles);
    t.min_edge = std::min(t.min_edge, s.min_edge);
    t.max_edge = std::max(t.max_edge, s.max_edge);
    t.closed = t.closed && s.closed;
    t.volume += s.volume, t.brep_volume += s.brep_volume, t.seconds += s.seconds, t.splits += s.splits;
  }
  std::vector<MeshSurfaceRun> meshes;
  for (const MeshCadRun& r : runs) {
    part.snap_seconds += r.snap_seconds;
    part.tessellations += r.tessellations;
    meshes.push_back(r.run);
  }
  merge_solid_runs(std::move(meshes), part.run);
  if (part.snapped) part.snap.quality = part.run.quality;
}

}  // namespace

MeshSolidsRun mesh_cad_solids(const std::vector<cad::Shape>& solids, const MeshCadOptions& opt, MeshSolidsRun* progress) {
  MeshSolidsRun local;
  MeshSolidsRun& r = progress ? *progress : local;
  if (opt.mesh.time_limit > 0) {
    MeshCadOptions inner = opt;
    inner.mesh.time_limit = 0;
    run_with_time_limit(opt.mesh.time_limit, [&] { mesh_cad_solids(solids, inner, &r); });
    return r;
  }
  r = MeshSolidsRun{};
  if (solids.empty()) throw InputError("no solid to mesh");
  check_size_numbers(solids, opt);
  r.touching = cad::touching_solids(solids, 1e-6);
  for (const auto& [a, b] : r.touching)
    if (opt.log)
      opt.log(1, "solids " + std::to_string(a) + " and " + std::to_string(b) +
                     " touch: their meshes are made one by one and do not conform where they meet");
  for (size_t k = 0; k < solids.size(); ++k) {
    MeshCadOptions one = options_of_solid(opt, solids[k]);
    const std::string prefix = "solid " + std::to_string(k + 1) + ": ";
    if (opt.log) one.log = [&opt, prefix](int level, const std::string& m) { opt.log(level, prefix + m); };
    r.solids.emplace_back();
    try {
      mesh_cad_part(solids[k], one, &r.solids.back());
    } catch (const InputError& e) {
      throw InputError(prefix + e.what());
    } catch (const GeometryError& e) {
      throw GeometryError(prefix + e.what());
    } catch (const MeshingError& e) {
      throw MeshingError(prefix + e.what());
    }
  }
  put_part_together(r.solids, r.part);
  return r;
}

}  // namespace hexdom::pipeline
