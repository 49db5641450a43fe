// Quality summary per cell type, as `hexdom quality` prints it.
#pragma once

#include <array>
#include <string>

#include "hexdom/mesh/mesh.h"
#include "hexdom/quality/metrics.h"

namespace hexdom::quality {

/// Figures for the cells of one type. With no cells, the minima/maxima are NaN.
struct TypeStats {
  int count = 0;
  double sj_min = 0, sj_mean = 0;
  int inverted = 0;  ///< scaled Jacobian <= 0, or degenerate (invalid SJ, a zero-length edge)
  double edge_ratio_min = 0, edge_ratio_max = 0;
  double volume = 0;
  /// Scaled-Jacobian histogram: 20 bins of width 0.1 over [-1, 1]; invalid cells in bin 0.
  std::array<int, 20> histogram{};
};

/// Figures for the second-order cells of one type (quality/second_order.h). With no cells, sj_min
/// is NaN.
struct SecondOrderStats {
  int count = 0;
  double sj_min = 0;  ///< the least second-order scaled Jacobian (nodes and Gauss points)
  int inverted = 0;   ///< cells whose second-order scaled Jacobian is <= 0 somewhere
  double volume = 0;  ///< of the curved cells
};

/// For a second-order mesh, hex / prism / tet hold the figures of the cells' corners (the straight
/// cells) and hex20 / wedge15 / tet10 those of the curved cells; total_volume is the curved cells'.
struct QualityReport {
  TypeStats hex, prism, tet;
  double total_volume = 0;
  bool second_order = false;
  SecondOrderStats hex20, wedge15, tet10;
};

/// The cells measured on `threads` threads (compute_metrics): the same report on any number.
QualityReport quality_report(const mesh::Mesh& mesh, int threads = 1);
/// Inverted cells of every type: of the curved cells in a second-order mesh.
inline int inverted_cells(const QualityReport& q) {
  return q.second_order ? q.hex20.inverted + q.wedge15.inverted + q.tet10.inverted
                        : q.hex.inverted + q.prism.inverted + q.tet.inverted;
}
/// The largest edge ratio (longest over shortest edge of a cell) over the cells of every type; 0
/// with no cells.
double max_edge_ratio(const QualityReport& q);
/// The least scaled Jacobian over the cells of every type (of the straight cells: the hex, prism
/// and tet sj_min; a NaN one passed over, as its cells count as inverted); 1 with no cells.
double worst_sj(const QualityReport& q);
/// Same, from metrics already computed for `mesh`.
QualityReport quality_report(const mesh::Mesh& mesh, const CellMetrics& metrics);

/// JSON object with keys "hex", "prism", "tet", each holding count, sj_min, sj_mean, inverted,
/// edge_ratio_min, edge_ratio_max, volume and histogram; "total_volume"; "order" (1 or 2) and, for
/// order 2, "hex20", "wedge15", "tet10", each holding count, sj_min, inverted and volume. NaN is
/// written null.
std::string to_json(const QualityReport& report);
/// A small table for people.
std::string to_text(const QualityReport& report);

}  // namespace hexdom::quality
