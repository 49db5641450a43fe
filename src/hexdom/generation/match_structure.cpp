// The surface's layout, the structure's vertices snapped onto its corners, and the structure's
// boundary faces matched to the surface's patches, with the patches' harmonic maps.
#include <algorithm>

#include "hexdom/generation/steps.h"
#include "hexdom/mesh/cell_faces.h"
#include "hexdom/polycube/match_faces.h"

namespace hexdom::generation {

namespace {

// The curve of the loop segment from corner position s0 to the next corner, along the loop.
Curve loop_curve(const mesh::SurfaceMesh& S, const polycube::Patch& patch, int s0, int len) {
  const int L = static_cast<int>(patch.loop.size());
  Curve cv;
  cv.p.push_back(S.V.row(patch.loop[s0]).transpose());
  cv.s.push_back(0);
  for (int k = 1; k <= len; ++k) {
    Vec3 q = S.V.row(patch.loop[(s0 + k) % L]).transpose();
    cv.s.push_back(cv.s.back() + (q - cv.p.back()).norm());
    cv.p.push_back(q);
  }
  return cv;
}

// Patch p's map onto its face (vertices fv in outward order; lc: the structure vertices of the
// patch's corners in loop order): the boundary, each loop segment between corners by arc length
// onto the domain edge; the curves between corners; the patch with local vertex numbers
// (increasing with the surface's, so the linear system is the one the whole surface's numbering
// gives), so that no per-patch array is surface-sized. `local_of` is scratch of the surface's size.
void add_map_job(GenerationState& g, int p, const std::vector<int>& fv, const std::vector<int>& lc, std::vector<int>& local_of) {
  const mesh::SurfaceMesh& S = g.S;
  const polycube::Patch& patch = g.layout.patches[p];
  const int m = static_cast<int>(fv.size());
  PatchMap& pm = g.maps[p];
  pm.tris = patch.triangles;
  for (int i = 0; i < m; ++i) pm.domain[fv[i]] = domain_corner(m, i);
  std::vector<int> bnd;
  std::vector<Eigen::Vector2d> bpos;
  const int L = static_cast<int>(patch.loop.size());
  for (size_t ci = 0; ci < patch.corners.size(); ++ci) {
    const int s0 = patch.corners[ci], s1 = patch.corners[(ci + 1) % patch.corners.size()];
    const int len = ((s1 - s0) % L + L) % L == 0 ? L : ((s1 - s0) % L + L) % L;
    Curve cv = loop_curve(S, patch, s0, len);
    const int va = lc[ci], vb = lc[(ci + 1) % m];
    const Eigen::Vector2d da = pm.domain[va], db = pm.domain[vb];
    for (int k = 0; k < len; ++k) {
      bnd.push_back(patch.loop[(s0 + k) % L]);
      const double t = cv.s.back() > 0 ? cv.s[k] / cv.s.back() : 0.0;
      bpos.push_back((1 - t) * da + t * db);
    }
    if (!g.curves.count({va, vb})) {
      Curve rev;
      rev.p.assign(cv.p.rbegin(), cv.p.rend());
      for (double x : cv.s) rev.s.insert(rev.s.begin(), cv.s.back() - x);
      g.curves[{va, vb}] = cv;
      g.curves[{vb, va}] = rev;
    }
  }
  for (int t : pm.tris)
    for (int k = 0; k < 3; ++k) pm.vertex.push_back(S.F(t, k));
  std::sort(pm.vertex.begin(), pm.vertex.end());
  pm.vertex.erase(std::unique(pm.vertex.begin(), pm.vertex.end()), pm.vertex.end());
  for (size_t i = 0; i < pm.vertex.size(); ++i) local_of[pm.vertex[i]] = static_cast<int>(i);
  MapJob job;
  job.patch = p;
  job.V.resize(static_cast<int>(pm.vertex.size()), 3);
  for (size_t i = 0; i < pm.vertex.size(); ++i) job.V.row(i) = S.V.row(pm.vertex[i]);
  pm.F.resize(static_cast<int>(pm.tris.size()), 3);
  for (size_t i = 0; i < pm.tris.size(); ++i)
    for (int k = 0; k < 3; ++k) pm.F(i, k) = local_of[S.F(pm.tris[i], k)];
  for (int& v : bnd) v = local_of[v];
  job.bnd = std::move(bnd);
  job.bc.resize(static_cast<int>(job.bnd.size()), 2);
  for (size_t i = 0; i < job.bnd.size(); ++i) job.bc.row(i) = bpos[i].transpose();
  g.jobs.push_back(std::move(job));
}

// Whether the loop's corners lc visit the face's vertices fv in the same cyclic order, forwards or
// backwards.
bool same_cycle(const std::vector<int>& lc, const std::vector<int>& fv) {
  const int m = static_cast<int>(fv.size());
  for (int r = 0; r < m; ++r) {
    bool fwd = true, bwd = true;
    for (int i = 0; i < m; ++i) {
      fwd = fwd && lc[(r + i) % m] == fv[i];
      bwd = bwd && lc[((r - i) % m + m) % m] == fv[i];
    }
    if (fwd || bwd) return true;
  }
  return false;
}

}  // namespace

void layout_surface(GenerationState& g) {
  polycube::check_closed_manifold(g.S);
  g.layout = polycube::patch_layout(g.S);
  g.diag = (g.S.V.colwise().maxCoeff() - g.S.V.colwise().minCoeff()).norm();
  g.stats.patches = static_cast<int>(g.layout.patches.size());
  g.stats.corners = static_cast<int>(g.layout.corners.size());
}

void snap_structure(GenerationState& g) {
  const mesh::SurfaceMesh& S = g.S;
  const mesh::Mesh& T = g.T;
  const polycube::PatchLayout& layout = g.layout;
  const int nb = T.num_cells(), nsv = T.num_nodes();
  if (nb == 0) throw GeometryError("the structure has no blocks");
  for (int b = 0; b < nb; ++b)
    if (!mesh::is_volume(T.type(b)))
      throw GeometryError("structure element " + std::to_string(b + 1) + " is a " + mesh::type_name(T.type(b)) +
                          ", not a hex, prism or tet block");
  g.P.resize(nsv);
  g.corner_vertex.assign(layout.corners.size(), -1);
  g.vertex_corner.assign(nsv, -1);
  std::vector<char> used(nsv, 0);
  for (int b = 0; b < nb; ++b)
    for (int i = 0; i < mesh::node_count(T.type(b)); ++i) used[T.cells(b, i)] = 1;
  for (int v = 0; v < nsv; ++v) {
    g.P[v] = T.V.row(v).transpose();
    if (!used[v]) continue;
    double best = g.opt.snap_tolerance * g.diag;
    int bc = -1;
    for (size_t c = 0; c < layout.corners.size(); ++c) {
      double d = (S.V.row(layout.corners[c]).transpose() - g.P[v]).norm();
      if (d <= best) { best = d; bc = static_cast<int>(c); }
    }
    if (bc < 0) { g.stats.interior_vertices++; continue; }
    if (g.corner_vertex[bc] >= 0)
      throw GeometryError("structure vertices " + std::to_string(g.corner_vertex[bc] + 1) + " and " + std::to_string(v + 1) +
                          " both snap to surface corner " + std::to_string(layout.corners[bc] + 1));
    g.corner_vertex[bc] = v;
    g.vertex_corner[v] = bc;
    g.P[v] = S.V.row(layout.corners[bc]).transpose();
  }
  for (size_t c = 0; c < layout.corners.size(); ++c)
    if (g.corner_vertex[c] < 0)
      throw GeometryError("surface corner at vertex " + std::to_string(layout.corners[c] + 1) + " (" +
                          std::to_string(S.V(layout.corners[c], 0)) + ", " + std::to_string(S.V(layout.corners[c], 1)) + ", " +
                          std::to_string(S.V(layout.corners[c], 2)) + ") has no structure vertex");
}

void match_faces(GenerationState& g) {
  const mesh::Mesh& T = g.T;
  const polycube::PatchLayout& layout = g.layout;
  // Each patch's corners as structure vertices, then the one matcher of block faces and patches.
  std::vector<std::vector<int>> corners(layout.patches.size());
  for (size_t p = 0; p < layout.patches.size(); ++p)
    for (int li : layout.patches[p].corners) corners[p].push_back(g.corner_vertex[layout.corner_of(layout.patches[p].loop[li])]);
  const std::vector<polycube::BlockFace> faces = polycube::block_faces(T);
  const polycube::FaceMatch match = polycube::match_faces_to_patches(faces, corners);
  if (!match.ok()) {
    const size_t more = match.problems.size() - 1;
    throw GeometryError(match.problems.front().message +
                        (more ? " (and " + std::to_string(more) + " more problem" + (more > 1 ? "s" : "") + ")" : std::string()));
  }
  // The boundary faces in the order of their sorted vertices: the order of the patch maps.
  std::vector<std::pair<std::vector<int>, int>> boundary;
  for (size_t i = 0; i < faces.size(); ++i) {
    if (match.patch_of_face[i] < 0) continue;
    std::vector<int> vs = faces[i].vertices;
    std::sort(vs.begin(), vs.end());
    boundary.emplace_back(std::move(vs), static_cast<int>(i));
  }
  std::sort(boundary.begin(), boundary.end());
  g.maps.resize(layout.patches.size());
  int bf_count = 0;
  std::vector<int> local_of(g.S.V.rows(), -1);  // surface vertex -> local vertex of the current patch
  for (const auto& [vs, i] : boundary) {
    const int b = faces[i].block, f = faces[i].face, p = match.patch_of_face[i];
    const polycube::Patch& patch = layout.patches[p];
    ++bf_count;
    g.boundary_face_patch[vs] = p;
    if (patch.num_loops != 1)
      throw GeometryError("patch " + std::to_string(p + 1) + " (label " + std::to_string(patch.label) + ") has " +
                          std::to_string(patch.num_loops) + " boundary loops: a patch must be a disk");
    // Face vertices in outward order and the loop's corners in loop order.
    const std::vector<int>& fv = faces[i].vertices;
    if (!same_cycle(corners[p], fv))
      throw GeometryError("patch " + std::to_string(p + 1) + " visits its corners in an order that does not match block " +
                          std::to_string(b + 1) + " face " + std::to_string(f + 1));
    add_map_job(g, p, fv, corners[p], local_of);
  }
  g.stats.boundary_faces = bf_count;
  // Boundary edges of the structure: edges of boundary faces.
  for (const auto& [vs, p] : g.boundary_face_patch) {
    (void)p;
    for (size_t i = 0; i < vs.size(); ++i)
      for (size_t j = i + 1; j < vs.size(); ++j) g.boundary_edges.insert({vs[i], vs[j]});
  }
}

void map_patches(GenerationState& g) {
  // Errors are reported in matching order, so the output does not depend on the thread count.
  solve_patch_maps(g.jobs, g.maps, g.nthreads);
  for (const MapJob& job : g.jobs) {
    if (job.error) std::rethrow_exception(job.error);
    if (job.result.flipped > 0)
      throw MeshingError("patch " + std::to_string(job.patch + 1) + " (label " + std::to_string(g.layout.patches[job.patch].label) +
                         "): the harmonic map flips " + std::to_string(job.result.flipped) +
                         " triangles even with mean-value weights");
    (job.result.weights == parametrization::Weights::Cotangent ? g.stats.cotangent_patches : g.stats.mean_value_patches)++;
  }
}

}  // namespace hexdom::generation
