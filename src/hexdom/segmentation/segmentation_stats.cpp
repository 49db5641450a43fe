#include "hexdom/segmentation/segmentation_stats.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include "hexdom/segmentation/axis_labels.h"
#include "hexdom/mesh/triangle_adjacency.h"

namespace hexdom::segmentation {

SegmentationStats segmentation_stats(const mesh::SurfaceMesh& s, const Eigen::VectorXi& label, double max_angle) {
  const int nf = static_cast<int>(s.F.rows());
  SegmentationStats st;
  st.max_angle = max_angle;
  const TriangleGeometry geo = triangle_geometry(s);
  const Eigen::MatrixXi TT = mesh::triangle_adjacency(s.F);
  const double cos_max = std::cos(max_angle * M_PI / 180.0);
  std::array<double, 6> within{};
  double total = 0, total_within = 0;
  for (int f = 0; f < nf; ++f) {
    const int l = label(f);
    int other[3], n = 0;
    for (int k = 0; k < 3; ++k) {
      const int g = TT(f, k);
      if (g >= 0 && label(g) != l) {
        other[n++] = label(g);
        if (g > f) st.boundary_length += (s.V.row(s.F(f, k)) - s.V.row(s.F(f, (k + 1) % 3))).norm();
      }
    }
    if ((n >= 2 && other[0] == other[1]) || (n == 3 && (other[0] == other[2] || other[1] == other[2]))) ++st.teeth;
    total += geo.area(f);
    if (l < 1 || l > 6) continue;
    st.label_area[l - 1] += geo.area(f);
    if (geo.normal.row(f).dot(label_axis(l)) >= cos_max - 1e-12) {
      within[l - 1] += geo.area(f);
      total_within += geo.area(f);
    }
  }
  st.axis_fraction = total > 0 ? total_within / total : 0;
  for (int l = 0; l < 6; ++l)
    st.label_axis_fraction[l] = st.label_area[l] > 0 ? within[l] / st.label_area[l] : std::numeric_limits<double>::quiet_NaN();
  // Regions.
  std::vector<int> region(nf, -1), stack, size;
  for (int f0 = 0; f0 < nf; ++f0) {
    if (region[f0] >= 0) continue;
    region[f0] = st.patches;
    stack.assign(1, f0);
    int n = 0;
    while (!stack.empty()) {
      const int f = stack.back();
      stack.pop_back();
      ++n;
      for (int k = 0; k < 3; ++k) {
        const int g = TT(f, k);
        if (g >= 0 && region[g] < 0 && label(g) == label(f)) {
          region[g] = st.patches;
          stack.push_back(g);
        }
      }
    }
    if (n < 10) ++st.small_patches;
    ++st.patches;
  }
  return st;
}

std::string to_text(const SegmentationStats& st) {
  char buf[256];
  std::string s;
  std::snprintf(buf, sizeof buf, "patches %d (%d of fewer than 10 triangles)\n", st.patches, st.small_patches);
  s += buf;
  std::snprintf(buf, sizeof buf, "boundary length %.6g, zig-zag triangles %d\n", st.boundary_length, st.teeth);
  s += buf;
  std::snprintf(buf, sizeof buf, "area within %.0f deg of its label's axis: %.2f%%\n", st.max_angle, 100 * st.axis_fraction);
  s += buf;
  for (int l = 0; l < 6; ++l) {
    if (!(st.label_area[l] > 0)) continue;
    std::snprintf(buf, sizeof buf, "  %s area %.6g, %.2f%% within\n", label_name(l + 1).c_str(), st.label_area[l],
                  100 * st.label_axis_fraction[l]);
    s += buf;
  }
  return s;
}

}  // namespace hexdom::segmentation
