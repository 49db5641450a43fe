#include "hexdom/segmentation/polycube_boundary.h"

#include <algorithm>
#include <iomanip>
#include <ostream>
#include <unordered_map>

#include "hexdom/io/text.h"
#include "hexdom/segmentation/axis_labels.h"
#include "hexdom/segmentation/patch_graph.h"

namespace hexdom::segmentation {

PolycubeBoundary polycube_boundary(const mesh::SurfaceMesh& s) {
  check_surface(s);
  const PatchGraph g = patch_graph(s);
  const auto& L = g.layout;
  PolycubeBoundary b;
  b.corner_vertices = L.corners;  // ascending (BoundaryGraph::corners)
  std::sort(b.corner_vertices.begin(), b.corner_vertices.end());
  std::unordered_map<int, int> corner_of;
  b.corners.resize(static_cast<int>(b.corner_vertices.size()), 3);
  for (int i = 0; i < static_cast<int>(b.corner_vertices.size()); ++i) {
    corner_of[b.corner_vertices[i]] = i;
    b.corners.row(i) = s.V.row(b.corner_vertices[i]);
  }
  std::vector<std::string> bad;
  int nbad = 0;
  for (int r = 0; r < g.num_patches(); ++r) {
    const auto& p = L.patches[r];
    const int n = static_cast<int>(p.corners.size());
    if (p.num_loops != 1 || g.euler[r] != 1 || (n != 3 && n != 4)) {
      if (++nbad <= 5)
        bad.push_back("patch " + std::to_string(r + 1) + " (part " + std::to_string(s.patch(p.triangles[0])) + ", " +
                      (p.num_loops != 1 || g.euler[r] != 1 ? "not a disk" : std::to_string(n) + " corners") + ")");
      continue;
    }
    PolycubeFace f;
    f.patch = r + 1;
    f.id = s.patch(p.triangles[0]);
    for (int c : p.corners) f.corners.push_back(corner_of.at(p.loop[c]));
    // Start where the original did: at the first corner met scanning the patch's triangles in order.
    int first = -1;
    for (int t : p.triangles)
      for (int k = 0; k < 3; ++k)
        if (L.corner_of(s.F(t, k)) >= 0 && (first < 0 || 3 * t + k < first)) first = 3 * t + k;
    const int start = corner_of.at(s.F(first / 3, first % 3));
    std::rotate(f.corners.begin(), std::find(f.corners.begin(), f.corners.end(), start), f.corners.end());
    b.faces.push_back(std::move(f));
  }
  if (nbad) {
    std::string list;
    for (size_t i = 0; i < bad.size(); ++i) list += (i ? ", " : "") + bad[i];
    throw GeometryError(std::to_string(nbad) + " patch" + (nbad > 1 ? "es are" : " is") +
                        " not a disk with 3 or 4 corners: " + list + (nbad > 5 ? ", ..." : "") +
                        " (hexdom check lists every violation)");
  }
  for (const PatchCurve& c : g.curves) {
    PolycubeEdge e;
    e.corners[0] = corner_of.at(c.vertices.front());
    e.corners[1] = corner_of.at(c.vertices.back());
    e.patches[0] = c.left + 1;
    e.patches[1] = c.right + 1;
    e.path = c.vertices;
    b.edges.push_back(std::move(e));
  }
  return b;
}

mesh::Mesh polycube_shells(const PolycubeBoundary& b) {
  mesh::MeshBuilder mb;
  for (const PolycubeFace& f : b.faces)
    mb.add(f.corners.size() == 3 ? mesh::CellType::Triangle : mesh::CellType::Quad, f.corners.data(), f.patch);
  return mb.finish(b.corners);
}

void write_corner_file(const std::string& path, const PolycubeBoundary& b) {
  io::write_atomically(path, false, [&](std::ostream& o) {
    o << std::setprecision(17);
    for (size_t i = 0; i < b.corner_vertices.size(); ++i)
      o << b.corner_vertices[i] << " " << b.corners(i, 0) << " " << b.corners(i, 1) << " " << b.corners(i, 2) << "\n";
  });
}

void write_edges_vtk(const std::string& path, const mesh::SurfaceMesh& s, const PolycubeBoundary& b) {
  // Points: every surface vertex the edges use, corners first.
  std::vector<int> points = b.corner_vertices;
  std::unordered_map<int, int> index;
  for (size_t i = 0; i < points.size(); ++i) index[points[i]] = static_cast<int>(i);
  for (const auto& e : b.edges)
    for (int v : e.path)
      if (index.try_emplace(v, static_cast<int>(points.size())).second) points.push_back(v);
  size_t line_size = 0;
  for (const auto& e : b.edges) line_size += e.path.size() + 1;
  io::write_atomically(path, false, [&](std::ostream& o) {
    o << "# vtk DataFile Version 3.0\nHexDom polycube corners and edges\nASCII\nDATASET POLYDATA\n";
    o << "POINTS " << points.size() << " double\n" << std::setprecision(17);
    for (int v : points) o << s.V(v, 0) << " " << s.V(v, 1) << " " << s.V(v, 2) << "\n";
    o << "VERTICES " << b.corner_vertices.size() << " " << 2 * b.corner_vertices.size() << "\n";
    for (size_t i = 0; i < b.corner_vertices.size(); ++i) o << "1 " << i << "\n";
    o << "LINES " << b.edges.size() << " " << line_size << "\n";
    for (const auto& e : b.edges) {
      o << e.path.size();
      for (int v : e.path) o << " " << index.at(v);
      o << "\n";
    }
    const size_t cells = b.corner_vertices.size() + b.edges.size();
    o << "CELL_DATA " << cells << "\n";
    for (int side = 0; side < 2; ++side) {
      o << "SCALARS patch_" << (side ? "b" : "a") << " int 1\nLOOKUP_TABLE default\n";
      for (size_t i = 0; i < b.corner_vertices.size(); ++i) o << "0\n";
      for (const auto& e : b.edges) o << e.patches[side] << "\n";
    }
  });
}

}  // namespace hexdom::segmentation
