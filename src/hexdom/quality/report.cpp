#include "hexdom/quality/report.h"

#include "hexdom/mesh/second_order.h"
#include "hexdom/quality/second_order.h"

#include <cmath>
#include <cstdio>
#include <limits>

namespace hexdom::quality {

using mesh::CellType;

namespace {

/// The curved cells' figures of a second-order mesh; total_volume becomes theirs.
void add_second_order(const mesh::Mesh& m, QualityReport& r) {
  r.second_order = true;
  r.total_volume = 0;
  for (SecondOrderStats* s : {&r.hex20, &r.wedge15, &r.tet10}) s->sj_min = std::numeric_limits<double>::quiet_NaN();
  double p[mesh::kMaxSecondOrderNodes][3];
  for (int c = 0; c < m.num_cells(); ++c) {
    const CellType t = m.type(c);
    SecondOrderStats* s = t == CellType::Hex ? &r.hex20 : t == CellType::Wedge ? &r.wedge15 : t == CellType::Tet ? &r.tet10 : nullptr;
    if (!s) continue;
    mesh::second_order_points(m, c, p);
    const double sj = second_order_scaled_jacobian(t, p), v = second_order_volume(t, p);
    s->count++;
    s->inverted += !(sj > 0);
    s->sj_min = std::isnan(s->sj_min) ? sj : std::min(s->sj_min, sj);
    s->volume += v;
    r.total_volume += v;
  }
}

}  // namespace

QualityReport quality_report(const mesh::Mesh& m, int threads) { return quality_report(m, compute_metrics(m, threads)); }

QualityReport quality_report(const mesh::Mesh& m, const CellMetrics& q) {
  QualityReport r;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (TypeStats* s : {&r.hex, &r.prism, &r.tet}) {
    s->sj_min = s->edge_ratio_min = nan;
    s->edge_ratio_max = nan;
  }
  double sum_sj[3] = {0, 0, 0};
  for (int c = 0; c < m.num_cells(); ++c) {
    TypeStats* s = nullptr;
    int k = 0;
    switch (m.type(c)) {
      case CellType::Hex: s = &r.hex; k = 0; break;
      case CellType::Wedge: s = &r.prism; k = 1; break;
      case CellType::Tet: s = &r.tet; k = 2; break;
      default: continue;
    }
    const double sj = q.scaled_jacobian(c), er = q.edge_ratio(c);
    // A zero-length edge (edge ratio DBL_MAX) makes a cell degenerate even where its scaled
    // Jacobian, as Verdict defines it for tets, comes out as a tiny positive rounding error.
    const bool bad = is_inverted(sj) || !(er < 1.0e30);
    // A degenerate cell (DBL_MAX) counts as -1 in the statistics, never as a perfect cell.
    const double sj_eff = bad && !(sj <= 0) ? -1.0 : sj;
    s->count++;
    s->inverted += bad;
    s->sj_min = std::isnan(s->sj_min) ? sj_eff : std::min(s->sj_min, sj_eff);
    sum_sj[k] += sj_eff;
    s->edge_ratio_min = std::isnan(s->edge_ratio_min) ? er : std::min(s->edge_ratio_min, er);
    s->edge_ratio_max = std::isnan(s->edge_ratio_max) ? er : std::max(s->edge_ratio_max, er);
    s->volume += q.volume(c);
    int bin = static_cast<int>(std::floor((std::max(-1.0, std::min(1.0, sj_eff)) + 1.0) / 0.1));
    s->histogram[std::max(0, std::min(19, bin))]++;
  }
  TypeStats* all[3] = {&r.hex, &r.prism, &r.tet};
  for (int k = 0; k < 3; ++k) {
    all[k]->sj_mean = all[k]->count ? sum_sj[k] / all[k]->count : nan;
    r.total_volume += all[k]->volume;
  }
  if (m.second_order()) add_second_order(m, r);
  return r;
}

double max_edge_ratio(const QualityReport& q) {
  double m = 0;
  for (const TypeStats* s : {&q.hex, &q.prism, &q.tet})
    if (s->count > 0) m = std::isnan(s->edge_ratio_max) ? std::numeric_limits<double>::infinity() : std::max(m, s->edge_ratio_max);
  return m;
}

double worst_sj(const QualityReport& q) {
  double w = 1;
  for (const TypeStats* t : {&q.hex, &q.prism, &q.tet})
    if (t->count > 0) w = std::min(w, t->sj_min);
  return w;
}

namespace {
std::string num(double v) {
  if (!std::isfinite(v)) return "null";
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}
}  // namespace

std::string to_json(const QualityReport& r) {
  std::string s = "{";
  const char* names[3] = {"hex", "prism", "tet"};
  const TypeStats* all[3] = {&r.hex, &r.prism, &r.tet};
  for (int k = 0; k < 3; ++k) {
    const TypeStats& t = *all[k];
    s += std::string(k ? ", " : "") + "\"" + names[k] + "\": {\"count\": " + std::to_string(t.count) +
         ", \"sj_min\": " + num(t.sj_min) + ", \"sj_mean\": " + num(t.sj_mean) +
         ", \"inverted\": " + std::to_string(t.inverted) + ", \"edge_ratio_min\": " +
         num(t.edge_ratio_min) + ", \"edge_ratio_max\": " + num(t.edge_ratio_max) +
         ", \"volume\": " + num(t.volume) + ", \"histogram\": [";
    for (int b = 0; b < 20; ++b) s += (b ? ", " : "") + std::to_string(t.histogram[b]);
    s += "]}";
  }
  s += ", \"total_volume\": " + num(r.total_volume) + ", \"order\": " + (r.second_order ? "2" : "1");
  if (r.second_order) {
    const char* names2[3] = {"hex20", "wedge15", "tet10"};
    const SecondOrderStats* all2[3] = {&r.hex20, &r.wedge15, &r.tet10};
    for (int k = 0; k < 3; ++k)
      s += std::string(", \"") + names2[k] + "\": {\"count\": " + std::to_string(all2[k]->count) + ", \"sj_min\": " +
           num(all2[k]->sj_min) + ", \"inverted\": " + std::to_string(all2[k]->inverted) + ", \"volume\": " +
           num(all2[k]->volume) + "}";
  }
  s += "}";
  return s;
}

std::string to_text(const QualityReport& r) {
  std::string s = "type     count   SJ min   SJ mean  inverted  edge ratio min..max\n";
  const char* names[3] = {"hex", "prism", "tet"};
  const TypeStats* all[3] = {&r.hex, &r.prism, &r.tet};
  char buf[160];
  for (int k = 0; k < 3; ++k) {
    const TypeStats& t = *all[k];
    if (!t.count) {
      std::snprintf(buf, sizeof buf, "%-6s %7d        -         -         -  -\n", names[k], 0);
    } else {
      std::snprintf(buf, sizeof buf, "%-6s %7d  %7.4f   %7.4f  %8d  %.3f .. %.3f\n", names[k], t.count,
                    t.sj_min, t.sj_mean, t.inverted, t.edge_ratio_min, t.edge_ratio_max);
    }
    s += buf;
  }
  if (r.second_order) {
    const char* names2[3] = {"hex20", "wedge15", "tet10"};
    const SecondOrderStats* all2[3] = {&r.hex20, &r.wedge15, &r.tet10};
    for (int k = 0; k < 3; ++k) {
      if (!all2[k]->count) continue;
      std::snprintf(buf, sizeof buf, "%-7s %6d  %7.4f            %8d  (second order: nodes and Gauss points)\n", names2[k],
                    all2[k]->count, all2[k]->sj_min, all2[k]->inverted);
      s += buf;
    }
  }
  std::snprintf(buf, sizeof buf, "volume %.10g\n", r.total_volume);
  return s + buf;
}

}  // namespace hexdom::quality
