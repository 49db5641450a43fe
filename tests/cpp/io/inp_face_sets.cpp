// write_inp's Face<k> sets, judged by CalculiX: a box as one hex, two wedges or six tets (and their
// second-order forms), its sides tagged as FreeCAD numbers a box's faces, fixed on one side's node
// set with a pressure on the opposite side's surface (*DSLOAD): the reaction CalculiX prints must
// balance the pressure times that side's area vector. A wrong Abaqus face number loads another
// face and the reaction points elsewhere. Skipped without ccx.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "hexdom/io/inp.h"
#include "hexdom/mesh/second_order.h"
#include "io_test_util.h"

using namespace hexdom;

namespace {

// A 2 x 1.5 x 1 box as one hex, two wedges or six tets (VTK orientation).
mesh::Mesh box(mesh::CellType t) {
  Eigen::MatrixXd V(8, 3);
  for (int i = 0; i < 8; ++i) V.row(i) << 2.0 * (i & 1), 1.5 * ((i >> 1) & 1), 1.0 * ((i >> 2) & 1);
  // Corner index i + 2j + 4k; VTK's hex order.
  const int h[8] = {0, 1, 3, 2, 4, 5, 7, 6};
  mesh::MeshBuilder b;
  if (t == mesh::CellType::Hex) {
    b.add(t, h, 1);
  } else if (t == mesh::CellType::Wedge) {  // first triangle facing away from the second
    const int w1[6] = {h[0], h[2], h[1], h[4], h[6], h[5]}, w2[6] = {h[0], h[3], h[2], h[4], h[7], h[6]};
    b.add(t, w1, 1);
    b.add(t, w2, 1);
  } else {  // Kuhn's six tets around the diagonal h0 - h6
    const int ring[7] = {h[1], h[2], h[3], h[7], h[4], h[5], h[1]};
    for (int k = 0; k < 6; ++k) {
      int tet[4] = {h[0], ring[k], ring[k + 1], h[6]};
      const Eigen::Vector3d a = V.row(tet[1]) - V.row(tet[0]), c = V.row(tet[2]) - V.row(tet[0]),
                            d = V.row(tet[3]) - V.row(tet[0]);
      if (a.cross(c).dot(d) < 0) std::swap(tet[1], tet[2]);
      b.add(t, tet, 1);
    }
  }
  return b.finish(V);
}

// The box side a boundary face lies on, numbered as FreeCAD numbers a box's faces: x = 0, x = max,
// y = 0, y = max, z = 0, z = max -> 1..6.
int side(const mesh::Mesh& m, const mesh::BoundaryFace& f) {
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (int i = 0; i < f.n; ++i) c += m.V.row(f.v[i]).transpose() / f.n;
  const double size[3] = {2.0, 1.5, 1.0};
  for (int k = 0; k < 3; ++k) {
    if (std::abs(c(k)) < 1e-9) return 2 * k + 1;
    if (std::abs(c(k) - size[k]) < 1e-9) return 2 * k + 2;
  }
  return 0;
}

// The total reaction force CalculiX prints for node set Face<fixed> when Face<loaded> carries
// pressure p.
Eigen::Vector3d reaction(const mesh::Mesh& m, const io::FaceSets& sets, int fixed, int loaded, double p,
                         const std::string& name) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(test::temp_path("ccx_" + name));
  fs::remove_all(dir);
  fs::create_directories(dir);
  io::write_inp((dir / "mesh.inp").string(), m, &sets);
  std::ofstream job(dir / "job.inp");
  job << "*INCLUDE, INPUT=mesh.inp\n*MATERIAL, NAME=M\n*ELASTIC\n1000, 0.3\n*SOLID SECTION, ELSET=EALL, MATERIAL=M\n"
      << "*STEP\n*STATIC\n*BOUNDARY\nFace" << fixed << ", 1, 3\n*DSLOAD\nFace" << loaded << ", P, " << p
      << "\n*NODE PRINT, NSET=Face" << fixed << ", TOTALS=ONLY\nRF\n*END STEP\n";
  job.close();
  const std::string cmd = "cd '" + dir.string() + "' && ccx job > ccx.log 2>&1";
  EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
  std::ifstream dat(dir / "job.dat");
  std::stringstream s;
  s << dat.rdbuf();
  std::smatch match;
  const std::string text = s.str();
  const std::regex re(R"(total force \(fx,fy,fz\) for set FACE\d+ and time\s+\S+\s+(\S+)\s+(\S+)\s+(\S+))");
  if (!std::regex_search(text, match, re)) {
    ADD_FAILURE() << "no total force in " << (dir / "job.dat") << ", see ccx.log beside it";
    return Eigen::Vector3d::Constant(std::nan(""));
  }
  return {std::stod(match[1]), std::stod(match[2]), std::stod(match[3])};
}

}  // namespace

TEST(InpFaceSets, CalculiXLoadsTheFaceEachSurfaceNames) {
  if (std::system("command -v ccx > /dev/null 2>&1") != 0) GTEST_SKIP() << "ccx (calculix-ccx) not installed";
  for (mesh::CellType t : {mesh::CellType::Hex, mesh::CellType::Wedge, mesh::CellType::Tet}) {
    for (int order : {1, 2}) {
      mesh::Mesh m = box(t);
      if (order == 2) m = mesh::add_mid_edge_nodes(m);
      io::FaceSets sets;
      sets.faces = mesh::boundary_faces(m);
      for (const mesh::BoundaryFace& f : sets.faces) sets.tag.push_back(side(m, f));
      // Fix one side, press on the opposite one (no shared node: CalculiX's reaction is then the
      // whole load): the reaction balances the pressure's force, 3 x the side's area vector.
      for (int fixed : {1, 3, 5}) {
        const int loaded = fixed + 1;
        Eigen::Vector3d expected = Eigen::Vector3d::Zero();
        for (size_t i = 0; i < sets.faces.size(); ++i)
          if (sets.tag[i] == loaded) expected += 3.0 * mesh::face_area_vector(m, sets.faces[i]);
        const std::string name = mesh::type_name(t) + std::to_string(order) + "_" + std::to_string(loaded);
        const Eigen::Vector3d r = reaction(m, sets, fixed, loaded, 3.0, name);
        EXPECT_LT((r - expected).norm(), 1e-6 * expected.norm())
            << name << ": reaction " << r.transpose() << ", expected " << expected.transpose();
      }
    }
  }
}
