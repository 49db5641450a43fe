#include "hexdom/io/face_sets.h"

#include "hexdom/mesh/closest_point.h"

namespace hexdom::io {

std::map<int, std::vector<size_t>> FaceSets::by_tag() const {
  std::map<int, std::vector<size_t>> out;
  for (size_t i = 0; i < faces.size() && i < tag.size(); ++i)
    if (tag[i] >= 1) out[tag[i]].push_back(i);
  return out;
}

FaceSets face_sets(const mesh::Mesh& mesh, const mesh::SurfaceMesh& surface) {
  FaceSets sets;
  if (surface.F.rows() == 0) return sets;
  sets.faces = mesh::boundary_faces(mesh);
  const std::vector<int> tris = mesh::nearest_triangles(mesh::TriangleProjector(surface.V, surface.F), mesh.V, sets.faces);
  sets.tag.reserve(tris.size());
  for (int t : tris) sets.tag.push_back(t >= 0 && t < surface.patch.size() ? surface.patch(t) : 0);
  return sets;
}

}  // namespace hexdom::io
