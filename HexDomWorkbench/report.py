"""Plain-text quality report of a mesh (FreeCAD-free), as HexDom_QualityReport shows it."""

import math

_TYPES = (("hex", "Hexahedra"), ("prism", "Prisms"), ("tet", "Tetrahedra"))
HISTOGRAM_BINS = 20  # core: bins of width 0.1 over [-1, 1], invalid cells in bin 0


def _num(value, fmt="{:.3f}"):
    if value is None or not math.isfinite(value):
        return "-"
    return fmt.format(value)


def format_quality_report(report, title=None):
    """Formats core.quality_report(...) as an aligned text table plus per-type histograms."""
    lines = []
    if title:
        lines += [title, "=" * len(title)]
    header = "{:<11} {:>8} {:>8} {:>8} {:>9} {:>9} {:>9}".format(
        "type", "count", "SJ min", "SJ mean", "inverted", "ER min", "ER max")
    lines += [header, "-" * len(header)]
    total = 0
    for key, name in _TYPES:
        s = report[key]
        total += s["count"]
        lines.append("{:<11} {:>8d} {:>8} {:>8} {:>9d} {:>9} {:>9}".format(
            name, s["count"], _num(s["sj_min"]), _num(s["sj_mean"]), s["inverted"],
            _num(s["edge_ratio_min"], "{:.2f}"), _num(s["edge_ratio_max"], "{:.2f}")))
    lines.append("{:<11} {:>8d}".format("all", total))
    lines.append("total volume: {}".format(_num(report.get("total_volume"), "{:.6g}")))
    lines.append("SJ = scaled Jacobian (1 ideal, <= 0 inverted); ER = edge ratio "
                 "(longest / shortest edge)")
    for key, name in _TYPES:
        s = report[key]
        hist = list(s.get("histogram", []))
        if not s["count"] or not hist:
            continue
        lines += ["", "{}: scaled Jacobian histogram".format(name)]
        peak = max(hist) or 1
        for b, n in enumerate(hist):
            if n == 0:
                continue
            lo = -1.0 + 0.1 * b
            lines.append("  [{:+.1f}, {:+.1f}) {:>7d} {}".format(
                lo, lo + 0.1, n, "#" * max(1, round(40 * n / peak))))
    return "\n".join(lines) + "\n"
