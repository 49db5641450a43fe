// Node orders between Gmsh's elements and VTK's cells, shared by the .msh reader and writer.
#pragma once

#include <algorithm>

namespace hexdom::io {

// Node orders: VTK node i of a cell is Gmsh node order[i]. Corners map through `corner`; a
// mid-edge node goes where VTK puts the mid node of the same edge.
struct GmshNodeOrders {
  int tet10[10], hex20[20], prism15[15];
  static constexpr int kIdentity[8] = {0, 1, 2, 3, 4, 5, 6, 7};
  static constexpr int kPrism[6] = {0, 2, 1, 3, 5, 4};  // Gmsh's prism is VTK's wedge mirrored

  GmshNodeOrders() {
    static const int vtk_tet[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};
    static const int gmsh_tet[6][2] = {{0, 1}, {1, 2}, {2, 0}, {3, 0}, {3, 2}, {3, 1}};
    static const int vtk_hex[12][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6},
                                       {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
    static const int gmsh_hex[12][2] = {{0, 1}, {0, 3}, {0, 4}, {1, 2}, {1, 5}, {2, 3},
                                        {2, 6}, {3, 7}, {4, 5}, {4, 7}, {5, 6}, {6, 7}};
    static const int vtk_wedge[9][2] = {{0, 1}, {1, 2}, {2, 0}, {3, 4}, {4, 5}, {5, 3}, {0, 3}, {1, 4}, {2, 5}};
    static const int gmsh_prism[9][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 4}, {2, 5}, {3, 4}, {3, 5}, {4, 5}};
    build(tet10, kIdentity, 4, vtk_tet, gmsh_tet, 6);
    build(hex20, kIdentity, 8, vtk_hex, gmsh_hex, 12);
    build(prism15, kPrism, 6, vtk_wedge, gmsh_prism, 9);
  }

  static void build(int* order, const int* corner, int nc, const int (*vtk)[2], const int (*gmsh)[2], int ne) {
    std::copy(corner, corner + nc, order);
    for (int e = 0; e < ne; ++e) {
      const int a = corner[vtk[e][0]], b = corner[vtk[e][1]];
      for (int g = 0; g < ne; ++g)
        if ((gmsh[g][0] == a && gmsh[g][1] == b) || (gmsh[g][0] == b && gmsh[g][1] == a)) order[nc + e] = nc + g;
    }
  }

  const int* of(long gmsh_type) const {
    switch (gmsh_type) {
      case 6: return kPrism;
      case 11: return tet10;
      case 17: return hex20;
      case 18: return prism15;
      default: return kIdentity;  // 2, 3, 4, 5: the same order
    }
  }
};

}  // namespace hexdom::io
