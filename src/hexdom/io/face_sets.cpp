#include "hexdom/io/face_sets.h"

#include <algorithm>
#include <iterator>

#include "hexdom/mesh/closest_point.h"

namespace hexdom::io {

std::map<int, std::vector<size_t>> FaceSets::by_tag() const {
  std::map<int, std::vector<size_t>> out;
  for (size_t i = 0; i < faces.size() && i < tag.size(); ++i)
    if (tag[i] >= 1) out[tag[i]].push_back(i);
  return out;
}

namespace {

const std::vector<int>* known(const std::vector<std::vector<int>>& node_faces, int v) {
  return v >= 0 && v < static_cast<int>(node_faces.size()) && !node_faces[v].empty() ? &node_faces[v] : nullptr;
}

std::vector<int> common(const std::vector<int>& a, const std::vector<int>& b) {
  std::vector<int> out;
  std::set_intersection(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(out));
  return out;
}

bool holds(const std::vector<int>& faces, int k) { return std::binary_search(faces.begin(), faces.end(), k); }

// The CAD faces all corners of f lie on (empty when a corner is not known or they share none);
// `all_known` whether every corner is known.
std::vector<int> shared_faces(const mesh::BoundaryFace& f, const std::vector<std::vector<int>>& node_faces, bool& all_known) {
  all_known = true;
  for (int i = 0; i < f.n; ++i) all_known = all_known && known(node_faces, f.v[i]);
  if (!all_known) return {};
  std::vector<int> out = node_faces[f.v[0]];
  for (int i = 1; i < f.n && !out.empty(); ++i) out = common(out, node_faces[f.v[i]]);
  return out;
}

// The nodes (increasing) of `faces` (indices into sets.faces, tagged `tag`), mid-edge nodes
// included, less those node_faces says lie on other CAD faces only (see face_sets).
std::vector<int> nodes_on(const mesh::Mesh& mesh, const FaceSets& sets, int tag, const std::vector<size_t>& faces,
                          const std::vector<std::vector<int>>& node_faces) {
  std::vector<int> nodes;
  for (size_t i : faces) {
    const mesh::BoundaryFace& f = sets.faces[i];
    const std::vector<int> own = mesh::face_nodes(mesh, f);
    for (size_t j = 0; j < own.size(); ++j) {
      bool on = true;
      if (j < static_cast<size_t>(f.n)) {
        const std::vector<int>* k = known(node_faces, own[j]);
        on = !k || holds(*k, tag);
      } else {  // the mid-edge node of the edge from corner j - n to the next
        const int a = f.v[j - f.n], b = f.v[(j - f.n + 1) % f.n];
        const std::vector<int>*ka = known(node_faces, a), *kb = known(node_faces, b);
        on = !ka || !kb || holds(common(*ka, *kb), tag);
      }
      if (on) nodes.push_back(own[j]);
    }
  }
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  return nodes;
}

}  // namespace

FaceSets face_sets(const mesh::Mesh& mesh, const mesh::SurfaceMesh& surface, const std::vector<std::vector<int>>& node_faces) {
  FaceSets sets;
  if (surface.F.rows() == 0) return sets;
  sets.faces = mesh::boundary_faces(mesh);
  const std::vector<int> tris = mesh::nearest_triangles(mesh::TriangleProjector(surface.V, surface.F), mesh.V, sets.faces);
  sets.tag.reserve(tris.size());
  sets.across.reserve(tris.size());
  for (size_t i = 0; i < tris.size(); ++i) {
    const int t = tris[i];
    const int nearest = t >= 0 && t < surface.patch.size() ? surface.patch(t) : 0;
    bool all_known = false;
    const std::vector<int> shared = shared_faces(sets.faces[i], node_faces, all_known);
    sets.tag.push_back(shared.empty() || holds(shared, nearest) ? nearest : shared.front());
    sets.across.push_back(all_known && shared.empty());
  }
  for (const auto& [tag, faces] : sets.by_tag()) sets.nodes[tag] = nodes_on(mesh, sets, tag, faces, node_faces);
  return sets;
}

std::vector<int> set_nodes(const mesh::Mesh& mesh, const FaceSets& sets, int tag) {
  const auto it = sets.nodes.find(tag);
  if (it != sets.nodes.end()) return it->second;
  const auto tagged = sets.by_tag();
  const auto faces = tagged.find(tag);
  return faces == tagged.end() ? std::vector<int>{} : nodes_on(mesh, sets, tag, faces->second, {});
}

}  // namespace hexdom::io
