#include "hexdom/io/surface_formats.h"

#include <array>
#include <cstdint>
#include <cstring>
#include <map>
#include <ostream>
#include <vector>

#include "hexdom/common/error.h"
#include "hexdom/io/text.h"

namespace hexdom::io {

namespace {

// The surface of vertices V, triangles F and a patch id per triangle.
mesh::SurfaceMesh to_surface(const std::vector<std::array<double, 3>>& V, const std::vector<std::array<int, 3>>& F,
                             const std::vector<int>& patch) {
  mesh::SurfaceMesh s;
  s.V.resize(static_cast<int>(V.size()), 3);
  for (size_t i = 0; i < V.size(); ++i) s.V.row(i) << V[i][0], V[i][1], V[i][2];
  s.F.resize(static_cast<int>(F.size()), 3);
  s.patch.resize(static_cast<int>(F.size()));
  for (size_t i = 0; i < F.size(); ++i) {
    s.F.row(i) << F[i][0], F[i][1], F[i][2];
    s.patch(i) = patch[i];
  }
  return s;
}

// Collects triangles with merged vertices.
struct SurfaceBuilder {
  std::map<std::array<double, 3>, int> index;
  std::vector<std::array<double, 3>> V;
  std::vector<std::array<int, 3>> F;
  std::vector<int> patch;

  int vertex(const std::array<double, 3>& p) {
    auto [it, inserted] = index.emplace(p, static_cast<int>(V.size()));
    if (inserted) V.push_back(p);
    return it->second;
  }
  mesh::SurfaceMesh finish() const { return to_surface(V, F, patch); }
};

}  // namespace

mesh::SurfaceMesh read_stl(const std::string& path) {
  const std::string data = load_file(path);
  SurfaceBuilder b;
  bool binary = data.size() >= 84;
  uint32_t n = 0;
  if (binary) {
    std::memcpy(&n, data.data() + 80, 4);
    binary = data.size() == 84 + 50ull * n;
  }
  if (binary) {
    for (uint32_t t = 0; t < n; ++t) {
      const char* rec = data.data() + 84 + 50ull * t;
      std::array<int, 3> f;
      for (int k = 0; k < 3; ++k) {
        float xyz[3];
        std::memcpy(xyz, rec + 12 + 12 * k, 12);
        std::array<double, 3> p{xyz[0], xyz[1], xyz[2]};
        for (double c : p)
          if (!std::isfinite(c)) throw InputError(path, 0, "triangle " + std::to_string(t + 1) + " has a non-finite coordinate");
        f[k] = b.vertex(p);
      }
      b.F.push_back(f);
      b.patch.push_back(1);
    }
  } else {
    if (!starts_with_ci(trim(std::string_view(data).substr(0, 80)), "solid"))
      throw InputError(path, 1, "not an STL file: binary size does not match its triangle count and the text does not start with 'solid'");
    LineCursor cur(path, data);
    std::string_view line;
    int solid = 0, nv = 0;
    std::array<int, 3> f{};
    bool in_facet = false;
    while (cur.next(line)) {
      auto w = split_ws(line);
      if (w.empty()) continue;
      std::string key = lower(w[0]);
      if (key == "solid") ++solid;
      else if (key == "facet") { in_facet = true; nv = 0; }
      else if (key == "vertex") {
        if (!in_facet || nv >= 3) cur.fail("vertex outside a facet or more than 3 vertices in a facet");
        if (w.size() < 4) cur.fail("vertex expects 3 coordinates");
        std::array<double, 3> p;
        for (int k = 0; k < 3; ++k)
          if (!parse_double(w[1 + k], p[k])) cur.fail("coordinate '" + std::string(w[1 + k]) + "' is not a finite number");
        f[nv++] = b.vertex(p);
      } else if (key == "endfacet") {
        if (nv != 3) cur.fail("facet has " + std::to_string(nv) + " vertices, expected 3");
        b.F.push_back(f);
        b.patch.push_back(solid);
        in_facet = false;
      } else if (key == "outer" || key == "endloop" || key == "endsolid") {
      } else {
        cur.fail("unexpected '" + std::string(w[0]) + "' in ASCII STL");
      }
    }
    if (in_facet) throw InputError(path, cur.line(), "file ends inside a facet (truncated?)");
  }
  if (b.F.empty()) throw InputError(path, 0, "no triangles");
  return b.finish();
}

void write_stl(const std::string& path, const mesh::SurfaceMesh& s) {
  write_atomically(path, true, [&](std::ostream& out) {
    char header[80] = "HexDom binary STL";
    out.write(header, 80);
    uint32_t n = static_cast<uint32_t>(s.F.rows());
    out.write(reinterpret_cast<const char*>(&n), 4);
    for (int t = 0; t < s.F.rows(); ++t) {
      Eigen::Vector3d a = s.V.row(s.F(t, 0)), b = s.V.row(s.F(t, 1)), c = s.V.row(s.F(t, 2));
      Eigen::Vector3d nrm = (b - a).cross(c - a);
      if (nrm.norm() > 0) nrm.normalize();
      float rec[12];
      for (int k = 0; k < 3; ++k) {
        rec[k] = static_cast<float>(nrm(k));
        rec[3 + k] = static_cast<float>(a(k));
        rec[6 + k] = static_cast<float>(b(k));
        rec[9 + k] = static_cast<float>(c(k));
      }
      out.write(reinterpret_cast<const char*>(rec), 48);
      uint16_t attr = 0;
      out.write(reinterpret_cast<const char*>(&attr), 2);
    }
  });
}

mesh::SurfaceMesh read_obj(const std::string& path) {
  const std::string data = load_file(path);
  LineCursor cur(path, data);
  std::vector<std::array<double, 3>> V;
  std::vector<std::array<int, 3>> F;
  std::vector<int> patch;
  std::map<std::string, int> groups;
  int current = 0;
  std::string_view line;
  while (cur.next(line)) {
    auto w = split_ws(line);
    if (w.empty() || w[0][0] == '#') continue;
    if (w[0] == "v") {
      if (w.size() < 4) cur.fail("'v' expects 3 coordinates");
      std::array<double, 3> p;
      for (int k = 0; k < 3; ++k)
        if (!parse_double(w[1 + k], p[k])) cur.fail("coordinate '" + std::string(w[1 + k]) + "' is not a finite number");
      V.push_back(p);
    } else if (w[0] == "f") {
      if (w.size() < 4) cur.fail("'f' expects at least 3 vertices");
      std::vector<int> idx;
      for (size_t k = 1; k < w.size(); ++k) {
        auto tok = w[k].substr(0, w[k].find('/'));
        long i;
        if (!parse_int(tok, i) || i == 0) cur.fail("face vertex '" + std::string(w[k]) + "' is not a valid index");
        long r = i > 0 ? i - 1 : static_cast<long>(V.size()) + i;
        if (r < 0 || r >= static_cast<long>(V.size()))
          cur.fail("face refers to vertex " + std::to_string(i) + ", but only " + std::to_string(V.size()) + " are defined so far");
        idx.push_back(static_cast<int>(r));
      }
      for (size_t k = 1; k + 1 < idx.size(); ++k) {
        F.push_back({idx[0], idx[k], idx[k + 1]});
        patch.push_back(current);
      }
    } else if (w[0] == "g" || w[0] == "o") {
      std::string name = w.size() > 1 ? std::string(w[1]) : "";
      long id;
      if (name.rfind("patch_", 0) == 0 && parse_int(std::string_view(name).substr(6), id)) {
        current = static_cast<int>(id);  // our own writer's group names keep their ids
      } else {
        auto [it, ins] = groups.emplace(name, static_cast<int>(groups.size()) + 1);
        current = it->second;
      }
    }
  }
  if (F.empty()) throw InputError(path, 0, "no faces");
  return to_surface(V, F, patch);
}

void write_obj(const std::string& path, const mesh::SurfaceMesh& s) {
  write_atomically(path, false, [&](std::ostream& out) {
    out.precision(17);
    out << "# HexDom surface\n";
    for (int i = 0; i < s.V.rows(); ++i) out << "v " << s.V(i, 0) << ' ' << s.V(i, 1) << ' ' << s.V(i, 2) << '\n';
    std::map<int, std::vector<int>> by_patch;
    for (int t = 0; t < s.F.rows(); ++t) by_patch[s.patch.size() ? s.patch(t) : 0].push_back(t);
    for (const auto& [p, faces] : by_patch) {
      out << "g patch_" << p << '\n';
      for (int t : faces) out << "f " << s.F(t, 0) + 1 << ' ' << s.F(t, 1) + 1 << ' ' << s.F(t, 2) + 1 << '\n';
    }
  });
}

}  // namespace hexdom::io
