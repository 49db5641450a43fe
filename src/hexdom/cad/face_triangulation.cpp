#include "hexdom/cad/face_triangulation.h"

#include <BRepAdaptor_Curve.hxx>
#include <BRepTools_WireExplorer.hxx>
#include <BRep_Tool.hxx>
#include <GCPnts_TangentialDeflection.hxx>
#include <Geom2d_Curve.hxx>
#include <Geom_Surface.hxx>
#include <ShapeAnalysis_Surface.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Wire.hxx>

#include <Eigen/Geometry>
#include <cmath>
#include <map>

#include "hexdom/common/format.h"
#include "hexdom/mesh/triangulate_polygon.h"

namespace hexdom::cad {

namespace {

using mesh::remesh::Kind;
using mesh::remesh::RVertex;
using V2 = Eigen::Vector2d;

Eigen::Vector3d vec(const gp_Pnt& p) { return {p.X(), p.Y(), p.Z()}; }

/// The face and what laying its boundary out in (u, v) needs.
struct Layout {
  const WorkShape& w;
  int fi;
  TopoDS_Face face;  ///< oriented FORWARD: its wires run counter-clockwise around the material in (u, v)
  Handle(Geom_Surface) surface;
  Handle(ShapeAnalysis_Surface) analysis;
  double tolerance = 1e-7;
  double u_period = 0, v_period = 0;  ///< 0 when not periodic
  double off_limit = 0;  ///< farthest a node's (u, v) point may lie from the node
  bool project_all = false;  ///< (u, v) of every node by projection, none from the pcurves
  Eigen::Vector3d at(const V2& uv) const { return vec(surface->Value(uv.x(), uv.y())); }
  [[noreturn]] void fail(const std::string& why) const {
    throw MeshingError(w.source + ": " + w.face_name(fi) + " cannot be triangulated: " + why);
  }
};

/// A node of a loop: its merged vertex and its (u, v).
struct LoopNode {
  int id;
  V2 uv;
};

/// Nodes for edge `ei` along its 3D curve when no BRepMesh triangulation gave it any: curve
/// vertices, or face vertices (with (u, v)) on a seam of the face.
void discretise_edge(const Layout& L, int ei, const Sizes& z, Merged& out) {
  const TopoDS_Edge E = TopoDS::Edge(L.w.edges(ei + 1));
  BRepAdaptor_Curve curve(E);
  GCPnts_TangentialDeflection td(curve, curve.FirstParameter(), curve.LastParameter(), std::min(z.angle > 0 ? z.angle : 0.5, 0.5),
                                 z.deflection, 2, 1e-9, 0.25 * z.min_size);
  // The deflection's parameters, pieces longer than the size cut evenly.
  std::vector<double> ts{curve.FirstParameter()};
  for (int k = 2; k <= td.NbPoints(); ++k) {
    const double t0 = ts.back(), t1 = k == td.NbPoints() ? curve.LastParameter() : td.Parameter(k);
    const int pieces = std::max(1, static_cast<int>(std::ceil(curve.Value(t0).Distance(curve.Value(t1)) / z.size)));
    for (int j = 1; j <= pieces; ++j) ts.push_back(t0 + (t1 - t0) * j / pieces);
  }
  if (ts.size() < 2) ts.push_back(curve.LastParameter());
  const int n = static_cast<int>(ts.size());
  TopoDS_Vertex v1, v2;
  TopExp::Vertices(E, v1, v2);
  std::vector<int>& en = out.edge_nodes[ei];
  std::vector<double>& ep = out.edge_params[ei];
  en.assign(n, -1);
  ep.resize(n);
  en.front() = L.w.vertices.FindIndex(v1) - 1;
  en.back() = L.w.vertices.FindIndex(v2) - 1;
  ep.front() = curve.FirstParameter();
  ep.back() = curve.LastParameter();
  const bool seam = BRep_Tool::IsClosed(E, L.face);
  double a = 0, b = 0;
  const Handle(Geom2d_Curve) pc = seam ? BRep_Tool::CurveOnSurface(E, L.face, a, b) : Handle(Geom2d_Curve)();
  for (int k = 1; k < n - 1; ++k) {
    const double t = ts[k];
    RVertex v;
    v.p = vec(curve.Value(t));
    if (seam && !pc.IsNull()) {
      const gp_Pnt2d uv = pc->Value(t);
      v.kind = Kind::Face;
      v.owner = L.fi;
      v.uv = {uv.X(), uv.Y()};
      v.has_uv = true;
    } else {
      v.kind = Kind::Curve;
      v.owner = ei;
      v.t = t;
    }
    ep[k] = t;
    en[k] = static_cast<int>(out.V.size());
    out.V.push_back(v);
  }
}

/// (u, v) of `p` near `prev`, a period away where that is nearer.
V2 project_near(const Layout& L, const Eigen::Vector3d& p, const V2* prev) {
  const gp_Pnt P(p.x(), p.y(), p.z());
  const gp_Pnt2d q = prev ? L.analysis->NextValueOfUV(gp_Pnt2d(prev->x(), prev->y()), P, L.tolerance)
                          : L.analysis->ValueOfUV(P, L.tolerance);
  V2 uv(q.X(), q.Y());
  if (prev) {
    if (L.u_period > 0) uv.x() += L.u_period * std::round((prev->x() - uv.x()) / L.u_period);
    if (L.v_period > 0) uv.y() += L.v_period * std::round((prev->y() - uv.y()) / L.v_period);
  }
  return uv;
}

/// Appends the nodes of oriented edge E to `loop` from its start up to, not including, its end;
/// (u, v) from E's curve on the face, or from projection where that strays from the nodes.
void add_edge(const Layout& L, const TopoDS_Edge& E, const Sizes& z, Merged& out, std::vector<LoopNode>& loop,
              V2& end_uv) {
  const int ei = L.w.edges.FindIndex(E) - 1;
  double a = 0, b = 0;
  const Handle(Geom2d_Curve) pc = BRep_Tool::CurveOnSurface(E, L.face, a, b);
  const bool reversed = E.Orientation() == TopAbs_REVERSED;
  std::vector<std::pair<int, double>> nodes;  // (vertex, parameter) from E's start to its end
  if (BRep_Tool::Degenerated(E)) {
    if (pc.IsNull()) L.fail("degenerated Edge" + std::to_string(ei + 1) + " has no curve on the face");
    const int vi = L.w.vertices.FindIndex(TopExp::FirstVertex(E)) - 1;
    nodes = {{vi, a}, {vi, b}};
  } else {
    if (out.edge_nodes[ei].empty()) discretise_edge(L, ei, z, out);
    const std::vector<int>& en = out.edge_nodes[ei];
    const std::vector<double>& ep = out.edge_params[ei];
    for (size_t k = 0; k < en.size(); ++k) nodes.push_back({en[k], ep[k]});
    if (ep.front() > ep.back()) std::reverse(nodes.begin(), nodes.end());
  }
  if (reversed) std::reverse(nodes.begin(), nodes.end());
  std::vector<V2> uv(nodes.size());
  bool on_surface = !pc.IsNull() && (!L.project_all || BRep_Tool::Degenerated(E));
  for (size_t k = 0; k < nodes.size() && on_surface; ++k) {
    const gp_Pnt2d q = pc->Value(nodes[k].second);
    uv[k] = {q.X(), q.Y()};
    on_surface = BRep_Tool::Degenerated(E) || (L.at(uv[k]) - out.V[nodes[k].first].p).norm() <= L.off_limit;
  }
  if (!on_surface) {  // a pcurve that strays from the 3D edge: project the nodes instead
    for (size_t k = 0; k < nodes.size(); ++k) {
      const V2* prev = k > 0 ? &uv[k - 1] : (loop.empty() ? nullptr : &end_uv);
      uv[k] = project_near(L, out.V[nodes[k].first].p, prev);
      const double off = (L.at(uv[k]) - out.V[nodes[k].first].p).norm();
      if (!(off <= L.off_limit))
        L.fail("Edge" + std::to_string(ei + 1) + fmt(" lies %g off the face's surface", off));
    }
  }
  if (!loop.empty() && (L.u_period > 0 || L.v_period > 0)) {  // continue from the previous edge's end
    V2 shift(0, 0);
    if (L.u_period > 0) shift.x() = L.u_period * std::round((end_uv.x() - uv[0].x()) / L.u_period);
    if (L.v_period > 0) shift.y() = L.v_period * std::round((end_uv.y() - uv[0].y()) / L.v_period);
    for (V2& q : uv) q += shift;
  }
  for (size_t k = 0; k + 1 < nodes.size(); ++k) loop.push_back({nodes[k].first, uv[k]});
  end_uv = uv.back();
}

/// The face's wires as loops of nodes; `gaps[i]` is how far loop i's end lies from its start in
/// (u, v) (a period on a face that has no seam edge, else about zero).
std::vector<std::vector<LoopNode>> face_loops(const Layout& L, const Sizes& z, Merged& out, std::vector<V2>& gaps) {
  std::vector<std::vector<LoopNode>> loops;
  for (TopExp_Explorer wx(L.face, TopAbs_WIRE); wx.More(); wx.Next()) {
    const TopoDS_Wire W = TopoDS::Wire(wx.Current());
    int edges = 0, ordered = 0;
    for (TopExp_Explorer ex(W, TopAbs_EDGE); ex.More(); ex.Next()) ++edges;
    std::vector<LoopNode> loop;
    V2 end_uv(0, 0);
    for (BRepTools_WireExplorer we(W, L.face); we.More(); we.Next(), ++ordered) add_edge(L, we.Current(), z, out, loop, end_uv);
    if (ordered != edges) L.fail(fmt("a wire's %.0f edges do not join into one loop (%.0f do)", edges, ordered));
    if (loop.size() < 2) continue;  // a wire of one degenerated or tiny edge encloses nothing
    gaps.push_back(end_uv - loop.front().uv);
    loops.push_back(std::move(loop));
  }
  return loops;
}

/// The loops that go once around a periodic surface (they end a period from where they start); any
/// other gap (a pcurve's end within tolerance of the next one's start) is closed by the last segment.
std::vector<int> open_loops(const Layout& L, const std::vector<V2>& gaps) {
  std::vector<int> open;
  for (size_t i = 0; i < gaps.size(); ++i)
    if ((L.u_period > 0 && std::abs(gaps[i].x()) > 0.5 * L.u_period) ||
        (L.v_period > 0 && std::abs(gaps[i].y()) > 0.5 * L.v_period))
      open.push_back(static_cast<int>(i));
  return open;
}

bool loops_cross(const std::vector<std::vector<LoopNode>>& loops) {
  std::vector<std::vector<V2>> uv(loops.size());
  for (size_t i = 0; i < loops.size(); ++i)
    for (const LoopNode& n : loops[i]) uv[i].push_back(n.uv);
  return mesh::loops_intersect(uv);
}

/// A periodic face bounded by two closed wires and no seam (a cylinder's side as two circles): a
/// seam from a node of the first loop to the nearest node of the second makes them one loop.
std::vector<LoopNode> join_by_seam(const Layout& L, const Sizes& z, std::vector<LoopNode> a, std::vector<LoopNode> b,
                                   const V2& gap_a, const V2& gap_b, Merged& out) {
  const bool along_u = std::abs(gap_a.x()) > std::abs(gap_a.y());
  const double period = along_u ? L.u_period : L.v_period;
  auto coord = [&](const V2& p) { return along_u ? p.x() : p.y(); };
  if (gap_a.dot(gap_b) >= 0) L.fail("its two wires run the same way around the periodic surface");
  // b's node nearest to a's first node across the period, b rotated to start there and shifted by
  // whole periods to lie beside it.
  size_t j = 0;
  double best = INFINITY;
  for (size_t k = 0; k < b.size(); ++k) {
    double d = coord(b[k].uv) - coord(a[0].uv);
    d -= period * std::round(d / period);
    if (std::abs(d) < best) best = std::abs(d), j = k;
  }
  std::vector<LoopNode> br;
  for (size_t k = 0; k < b.size(); ++k) {
    LoopNode n = b[(j + k) % b.size()];
    if (j + k >= b.size()) n.uv += gap_b;
    br.push_back(n);
  }
  double shift = coord(a[0].uv) - coord(br[0].uv);
  shift = period * std::round(shift / period);
  for (LoopNode& n : br) (along_u ? n.uv.x() : n.uv.y()) += shift;
  // Seam nodes from a's first node to br's first, about one size apart.
  const V2 s0 = a[0].uv, s1 = br[0].uv;
  const int pieces = std::max(1, static_cast<int>(std::ceil((L.at(s0) - L.at(s1)).norm() / z.size)));
  std::vector<LoopNode> seam;
  for (int k = 1; k < pieces; ++k) {
    RVertex v;
    v.uv = s0 + (s1 - s0) * (static_cast<double>(k) / pieces);
    v.p = L.at(v.uv);
    v.kind = Kind::Face;
    v.owner = L.fi;
    v.has_uv = true;
    seam.push_back({static_cast<int>(out.V.size()), v.uv});
    out.V.push_back(v);
  }
  // a, across the seam shifted by a's gap, b from its start shifted likewise, b's end, back down the seam.
  std::vector<LoopNode> joined = a;
  joined.push_back({a[0].id, a[0].uv + gap_a});
  for (const LoopNode& n : seam) joined.push_back({n.id, n.uv + gap_a});
  for (const LoopNode& n : br) joined.push_back({n.id, n.uv + gap_a});
  joined.push_back({br[0].id, br[0].uv + gap_a + gap_b});
  for (auto it = seam.rbegin(); it != seam.rend(); ++it) joined.push_back(*it);
  return joined;
}

/// A triangulation in (u, v) of one face: nodes (merged vertex, or -1 for one made here), triangles.
struct Patch {
  std::vector<int> id;
  std::vector<V2> uv;
  std::vector<Eigen::Vector3d> p;
  std::vector<std::array<int, 3>> tris;
  V2 scale{1, 1};  ///< (u, v) times scale is about the surface's metric
  double area(int a, int b, int c) const {
    const V2 x = uv[a].cwiseProduct(scale), y = uv[b].cwiseProduct(scale), z = uv[c].cwiseProduct(scale);
    return 0.5 * ((y - x).x() * (z - x).y() - (y - x).y() * (z - x).x());
  }
  double min_angle(int a, int b, int c) const {
    const V2 x = uv[a].cwiseProduct(scale), y = uv[b].cwiseProduct(scale), z = uv[c].cwiseProduct(scale);
    auto ang = [](const V2& u, const V2& v) { return std::atan2(std::abs(u.x() * v.y() - u.y() * v.x()), u.dot(v)); };
    return std::min({ang(y - x, z - x), ang(x - y, z - y), ang(x - z, y - z)});
  }
};

using EdgeTris = std::map<std::pair<int, int>, std::vector<int>>;
EdgeTris edge_triangles(const Patch& P) {
  EdgeTris m;
  for (size_t t = 0; t < P.tris.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int a = P.tris[t][k], b = P.tris[t][(k + 1) % 3];
      m[{std::min(a, b), std::max(a, b)}].push_back(static_cast<int>(t));
    }
  return m;
}

int third(const std::array<int, 3>& t, int a, int b) {
  for (int v : t)
    if (v != a && v != b) return v;
  return -1;
}

/// Flips inner edges where that raises the smaller of the two triangles' smallest angles (in the
/// scaled (u, v)) and keeps both triangles counter-clockwise.
void flip_edges(Patch& P) {
  for (int pass = 0; pass < 20; ++pass) {
    const EdgeTris et = edge_triangles(P);
    std::vector<char> touched(P.tris.size(), 0);
    int flips = 0;
    for (const auto& [e, ts] : et) {
      if (ts.size() != 2 || touched[ts[0]] || touched[ts[1]]) continue;
      // Orient: ts[0] holds a -> b, ts[1] holds b -> a.
      int a = e.first, b = e.second, t0 = ts[0], t1 = ts[1];
      const auto& x = P.tris[t0];
      const bool ab = (x[0] == a && x[1] == b) || (x[1] == a && x[2] == b) || (x[2] == a && x[0] == b);
      if (!ab) std::swap(t0, t1);
      const int c = third(P.tris[t0], a, b), d = third(P.tris[t1], a, b);
      if (c == d || P.area(c, d, b) <= 0 || P.area(d, c, a) <= 0) continue;
      const double before = std::min(P.min_angle(a, b, c), P.min_angle(b, a, d));
      const double after = std::min(P.min_angle(c, d, b), P.min_angle(d, c, a));
      if (after <= before + 1e-9) continue;
      P.tris[t0] = {c, d, b};
      P.tris[t1] = {d, c, a};
      touched[t0] = touched[t1] = 1;
      ++flips;
    }
    if (flips == 0) return;
  }
}

/// Splits inner edges longer than `size` (in 3D) at their (u, v) midpoints, longest first, each
/// round followed by flips, until none is or the patch has `max_tris` triangles.
void refine(const Layout& L, Patch& P, double size, size_t max_tris) {
  flip_edges(P);
  for (int pass = 0; pass < 100 && P.tris.size() < max_tris; ++pass) {
    const EdgeTris et = edge_triangles(P);
    std::vector<std::pair<double, std::pair<int, int>>> longs;
    auto longest = [&](int t) {
      const auto& x = P.tris[t];
      return std::max({(P.p[x[0]] - P.p[x[1]]).norm(), (P.p[x[1]] - P.p[x[2]]).norm(), (P.p[x[2]] - P.p[x[0]]).norm()});
    };
    for (const auto& [e, ts] : et) {
      if (ts.size() != 2) continue;
      // Only an edge that is the longest of both its triangles (Rivara's bisection): near a long
      // boundary segment, which stays, the splits would otherwise creep towards it.
      const double len = (P.p[e.first] - P.p[e.second]).norm();
      if (len > size && len >= longest(ts[0]) && len >= longest(ts[1])) longs.push_back({len, e});
    }
    if (longs.empty()) return;
    std::sort(longs.rbegin(), longs.rend());
    std::vector<char> touched(P.tris.size(), 0);
    for (const auto& [len, e] : longs) {
      const std::vector<int>& ts = et.at(e);
      if (touched[ts[0]] || touched[ts[1]] || P.tris.size() >= max_tris) continue;
      const int a = e.first, b = e.second;
      const V2 uv = 0.5 * (P.uv[a] + P.uv[b]);
      const int m = static_cast<int>(P.uv.size());
      P.id.push_back(-1), P.uv.push_back(uv), P.p.push_back(L.at(uv));
      std::vector<std::array<int, 3>> made;
      for (int t : ts) {
        std::array<int, 3> x = P.tris[t], y = P.tris[t];
        for (int k = 0; k < 3; ++k) {
          if (x[k] == b) x[k] = m;
          if (y[k] == a) y[k] = m;
        }
        made.push_back(x), made.push_back(y);
      }
      bool ok = true;
      for (const auto& t : made) ok = ok && P.area(t[0], t[1], t[2]) > 0;
      if (!ok) {
        P.id.pop_back(), P.uv.pop_back(), P.p.pop_back();
        continue;
      }
      P.tris[ts[0]] = made[0], P.tris[ts[1]] = made[2];
      P.tris.push_back(made[1]), P.tris.push_back(made[3]);
      touched[ts[0]] = touched[ts[1]] = 1;
      touched.push_back(1), touched.push_back(1);
    }
    flip_edges(P);
  }
}

/// The face's surface and periods, and how far its boundary may stray from it.
Layout make_layout(const WorkShape& w, int fi, const Sizes& z) {
  Layout L{w, fi, TopoDS::Face(w.faces(fi + 1).Oriented(TopAbs_FORWARD)), {}, {}};
  L.surface = BRep_Tool::Surface(L.face);
  if (L.surface.IsNull()) L.fail("it has no surface");
  L.analysis = new ShapeAnalysis_Surface(L.surface);
  L.tolerance = std::max(BRep_Tool::Tolerance(L.face), 1e-9);
  double edge_tolerance = L.tolerance;
  for (TopExp_Explorer ex(L.face, TopAbs_EDGE); ex.More(); ex.Next())
    edge_tolerance = std::max(edge_tolerance, BRep_Tool::Tolerance(TopoDS::Edge(ex.Current())));
  if (L.surface->IsUPeriodic()) L.u_period = L.surface->UPeriod();
  if (L.surface->IsVPeriodic()) L.v_period = L.surface->VPeriod();
  L.off_limit = std::max(10 * edge_tolerance, 0.02 * z.size);
  return L;
}

}  // namespace

void triangulate_face(const WorkShape& w, int fi, const Sizes& z, Merged& out) {
  Layout L = make_layout(w, fi, z);
  const size_t vertices_before = out.V.size();
  std::vector<V2> gaps;
  std::vector<std::vector<LoopNode>> loops = face_loops(L, z, out, gaps);
  std::vector<int> open = open_loops(L, gaps);
  if (open.empty() && loops_cross(loops) && !L.project_all) {
    // pcurves that stay near their edges yet cross each other: the projected nodes instead (the
    // edges have their nodes by now, so this makes no new vertices).
    L.project_all = true;
    gaps.clear();
    loops = face_loops(L, z, out, gaps);
    open = open_loops(L, gaps);
  }
  if (loops.empty()) L.fail("it has no wire that encloses anything");
  if (open.size() == 2) {
    loops[open[0]] = join_by_seam(L, z, loops[open[0]], loops[open[1]], gaps[open[0]], gaps[open[1]], out);
    loops.erase(loops.begin() + open[1]);
  } else if (!open.empty()) {
    L.fail(fmt("%.0f of its wires go once around the periodic surface without a seam (two can be joined by one)",
               static_cast<double>(open.size())));
  }
  Patch P;
  std::vector<std::vector<V2>> uv_loops;
  for (const auto& l : loops) {
    uv_loops.emplace_back();
    for (const LoopNode& n : l) {
      P.id.push_back(n.id), P.uv.push_back(n.uv), P.p.push_back(out.V[n.id].p);
      uv_loops.back().push_back(n.uv);
    }
  }
  // Scale (u, v) to the surface's metric at the middle of the loops' box.
  Eigen::AlignedBox2d box;
  for (const V2& uv : P.uv) box.extend(uv);
  gp_Pnt c;
  gp_Vec du, dv;
  L.surface->D1(box.center().x(), box.center().y(), c, du, dv);
  P.scale = {du.Magnitude() > 1e-12 ? du.Magnitude() : 1.0, dv.Magnitude() > 1e-12 ? dv.Magnitude() : 1.0};
  for (auto& l : uv_loops)
    for (V2& uv : l) uv = uv.cwiseProduct(P.scale);
  std::string why;
  P.tris = mesh::triangulate_polygon(uv_loops, &why);
  if (P.tris.empty()) L.fail("its boundary in the surface's parameters cannot be triangulated: " + why);
  double area = 0;  // the surface's, from (u, v) areas and the metric at the triangles' centroids
  for (const auto& t : P.tris) {
    const V2 m = (P.uv[t[0]] + P.uv[t[1]] + P.uv[t[2]]) / 3.0;
    L.surface->D1(m.x(), m.y(), c, du, dv);
    area += std::abs(P.area(t[0], t[1], t[2])) * du.Crossed(dv).Magnitude() / (P.scale.x() * P.scale.y());
  }
  refine(L, P, z.size, 2 * P.tris.size() + static_cast<size_t>(20 * area / (z.size * z.size)) + 100);
  for (size_t i = 0; i < P.id.size(); ++i) {
    if (P.id[i] >= 0) continue;
    RVertex v;
    v.p = P.p[i];
    v.uv = P.uv[i];
    v.has_uv = true;
    v.kind = Kind::Face;
    v.owner = fi;
    P.id[i] = static_cast<int>(out.V.size());
    out.V.push_back(v);
  }
  const bool flip = w.faces(fi + 1).Orientation() == TopAbs_REVERSED;
  int added = 0;
  for (auto t : P.tris) {
    std::array<int, 3> tri{P.id[t[0]], P.id[t[1]], P.id[t[2]]};
    if (flip) std::swap(tri[1], tri[2]);
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2]) {
      ++out.dropped;
      continue;
    }
    out.F.push_back(tri);
    out.face_of.push_back(fi);
    ++added;
  }
  if (added == 0) {
    out.V.resize(vertices_before);
    L.fail("its triangles in the surface's parameters all collapse in space");
  }
}

}  // namespace hexdom::cad
