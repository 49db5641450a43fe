#include "hexdom/polycube/match_faces.h"

#include <algorithm>
#include <map>

#include "hexdom/common/error.h"
#include "hexdom/mesh/cell_faces.h"

namespace hexdom::polycube {

namespace {

std::string vertex_list(const std::vector<int>& vs) {
  std::string out;
  for (int v : vs) out += (out.empty() ? "" : " ") + std::to_string(v + 1);
  return out;
}

std::string block_list(const std::vector<BlockFace>& faces, const std::vector<int>& uses) {
  std::string out;
  for (int i : uses) out += (out.empty() ? "" : ", ") + std::to_string(faces[i].block + 1);
  return out;
}

}  // namespace

std::string kind_name(MatchProblemKind kind) {
  switch (kind) {
    case MatchProblemKind::PatchesShareCorners: return "patches_share_corners";
    case MatchProblemKind::FaceInManyBlocks: return "face_in_many_blocks";
    case MatchProblemKind::FaceOnNoPatch: return "face_on_no_patch";
    case MatchProblemKind::PatchOnNoFace: return "patch_on_no_face";
    case MatchProblemKind::PatchOnManyFaces: return "patch_on_many_faces";
  }
  return "?";
}

std::vector<BlockFace> block_faces(const mesh::Mesh& structure) {
  std::vector<BlockFace> out;
  for (int b = 0; b < structure.num_cells(); ++b) {
    if (!mesh::is_volume(structure.type(b)))
      throw GeometryError("structure element " + std::to_string(b + 1) + " is a " + mesh::type_name(structure.type(b)) +
                          ", not a hex, prism or tet block");
    const auto [faces, n] = mesh::cell_faces(structure.type(b));
    for (int f = 0; f < n; ++f) {
      BlockFace bf{b, f, {}};
      for (int i = 0; i < faces[f].n; ++i) bf.vertices.push_back(structure.cells(b, faces[f].v[i]));
      out.push_back(std::move(bf));
    }
  }
  return out;
}

FaceMatch match_faces_to_patches(const std::vector<BlockFace>& faces, const std::vector<std::vector<int>>& patch_corners) {
  const int np = static_cast<int>(patch_corners.size()), nf = static_cast<int>(faces.size());
  FaceMatch out;
  out.face_of_patch.assign(np, -1);
  out.patch_of_face.assign(nf, -1);
  // Patches by their sorted corners; a later patch with an earlier one's corners is a problem.
  std::map<std::vector<int>, int> patch_of;
  std::vector<std::vector<int>> sorted_corners(np);
  std::vector<char> shadowed(np, 0);
  for (int p = 0; p < np; ++p) {
    std::vector<int>& vs = sorted_corners[p];
    vs = patch_corners[p];
    std::sort(vs.begin(), vs.end());
    auto [it, fresh] = patch_of.emplace(vs, p);
    if (fresh) continue;
    shadowed[p] = 1;
    out.problems.push_back({MatchProblemKind::PatchesShareCorners, {it->second, p}, {}, vs,
                            "patches " + std::to_string(it->second + 1) + " and " + std::to_string(p + 1) +
                                " have the same corners (" + vertex_list(vs) + ")"});
  }
  // Faces by their sorted vertices: every use, in the order given.
  std::map<std::vector<int>, std::vector<int>> uses;
  for (int i = 0; i < nf; ++i) {
    std::vector<int> vs = faces[i].vertices;
    std::sort(vs.begin(), vs.end());
    uses[std::move(vs)].push_back(i);
  }
  std::vector<std::vector<int>> uses_of_patch(np);
  for (const auto& [vs, us] : uses) {
    auto it = patch_of.find(vs);
    if (it != patch_of.end()) {
      uses_of_patch[it->second] = us;
      if (us.size() == 1) {
        out.face_of_patch[it->second] = us[0];
        out.patch_of_face[us[0]] = it->second;
      }
      continue;
    }
    const BlockFace& first = faces[us[0]];
    if (us.size() > 2)
      out.problems.push_back({MatchProblemKind::FaceInManyBlocks, {}, us, vs,
                              "face (vertices " + vertex_list(vs) + ") is in " + std::to_string(us.size()) + " blocks (" +
                                  block_list(faces, us) + ")"});
    else if (us.size() == 1)
      out.problems.push_back({MatchProblemKind::FaceOnNoPatch, {}, us, vs,
                              "block " + std::to_string(first.block + 1) +
                                  (first.face >= 0 ? " face " + std::to_string(first.face + 1) : std::string()) +
                                  " (vertices " + vertex_list(vs) +
                                  ") is on the boundary but matches no patch: no patch has exactly these corners"});
  }
  for (int p = 0; p < np; ++p) {
    if (shadowed[p]) continue;
    const std::vector<int>& us = uses_of_patch[p];
    if (us.empty())
      out.problems.push_back({MatchProblemKind::PatchOnNoFace, {p}, {}, sorted_corners[p],
                              "patch " + std::to_string(p + 1) + " (corners " + vertex_list(sorted_corners[p]) +
                                  ") matches no boundary face of the structure"});
    else if (us.size() > 1)
      out.problems.push_back({MatchProblemKind::PatchOnManyFaces, {p}, us, sorted_corners[p],
                              "patch " + std::to_string(p + 1) + " (corners " + vertex_list(sorted_corners[p]) +
                                  ") is a face of " + std::to_string(us.size()) + " blocks (" + block_list(faces, us) + ")"});
  }
  return out;
}

}  // namespace hexdom::polycube
