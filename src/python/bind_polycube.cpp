// _hexdom's polycube functions: the matching of a structure's block faces to its patches (the
// polycube boundary of a segmentation is bound with the segmentation, bind_segmentation.cpp).
// Vertex, block and patch indices 0-based.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "bindings.h"
#include "hexdom/mesh/cell_faces.h"
#include "hexdom/polycube/match_faces.h"

namespace py = pybind11;

namespace hexdom::python {

void bind_polycube(py::module_& m) {
  m.def("cell_faces",
        [](int vtk_type) {
          const mesh::CellType t = static_cast<mesh::CellType>(vtk_type);
          if (!mesh::is_volume(t)) throw GeometryError("cell type " + std::to_string(vtk_type) + " is not a hex (12), wedge (13) or tet (10)");
          std::vector<std::vector<int>> out;
          auto [faces, n] = mesh::cell_faces(t);
          for (int f = 0; f < n; ++f) out.emplace_back(faces[f].v, faces[f].v + faces[f].n);
          return out;
        },
        py::arg("vtk_type"),
        "The faces of a hex (12), wedge (13) or tet (10) as local node lists in VTK order, each outward\n"
        "(right-hand normal out of the cell): the core's one face table (mesh::cell_faces).");

  m.def("match_faces_to_patches",
        [](const std::vector<std::pair<int, std::vector<int>>>& faces, const std::vector<std::vector<int>>& patch_corners) {
          std::vector<polycube::BlockFace> fs;
          fs.reserve(faces.size());
          for (const auto& [block, vertices] : faces) fs.push_back({block, -1, vertices});
          const polycube::FaceMatch match = polycube::match_faces_to_patches(fs, patch_corners);
          py::list problems;
          for (const polycube::MatchProblem& p : match.problems) {
            py::dict d;
            d["kind"] = polycube::kind_name(p.kind);
            d["patches"] = p.patches;
            d["faces"] = p.faces;
            d["vertices"] = p.vertices;
            d["message"] = p.message;
            problems.append(d);
          }
          py::dict d;
          d["problems"] = problems;
          d["face_of_patch"] = match.face_of_patch;
          d["patch_of_face"] = match.patch_of_face;
          return d;
        },
        py::arg("faces"), py::arg("patch_corners"),
        "Matches block faces to patches by their corners (polycube::match_faces_to_patches). faces: (block,\n"
        "vertices) pairs, every face of every block; patch_corners: each patch's corner vertices. Returns a\n"
        "dict: problems (dicts: kind patches_share_corners / face_in_many_blocks / face_on_no_patch /\n"
        "patch_on_no_face / patch_on_many_faces, patches (0-based), faces (indices into `faces`: the uses of\n"
        "the face), vertices (sorted), message), face_of_patch and patch_of_face (-1: none).");
}

}  // namespace hexdom::python
