// Second-order meshes of a CAD part: the mid-edge nodes of the mesh boundary on the B-rep, as FEM
// solvers need them for curved faces (a circle spanned by 16 straight edges encloses 2.5% less).
#pragma once

#include "hexdom/cad/shape.h"
#include "hexdom/cad/snap.h"
#include "hexdom/mesh/mesh.h"
#include "hexdom/optimize/curve_mid_nodes.h"
#include "hexdom/quality/report.h"

namespace hexdom::cad {

struct SecondOrderResult {
  mesh::Mesh mesh;  ///< second order
  optimize::SecondOrderReport report;
  quality::QualityReport quality;  ///< of `mesh`
};

/// The first-order mesh `snapped` (snapped by snap_to_brep with the same `shape` and `tessellation`;
/// `kind` and `entity` its SnapResult's: which CAD edge or vertex each boundary corner is on) made
/// second order (mesh::add_mid_edge_nodes), the mid-edge node of every boundary edge then put on
/// the B-rep: on the nearest point of the CAD edge both ends lie on (a node on a CAD vertex lies on
/// that vertex's edges) when that point is nearer to the edge's midpoint than half the edge's
/// length; otherwise on the nearest point of the CAD face of the boundary faces around the edge
/// (each boundary face takes the face of the tessellation triangle nearest its centre, as the snap
/// classifies them; the nearer of two). The interior mid-edge nodes stay at the midpoints;
/// optimize::curve_mid_nodes keeps every cell at least at min(curve.min_sj, its straight value).
/// Throws InputError for a second-order input, kinds that do not match the mesh, or a tessellation
/// naming a face the shape lacks.
SecondOrderResult second_order_on_brep(const Shape& shape, const mesh::Mesh& snapped, const std::vector<SnapKind>& kind,
                                       const std::vector<int>& entity, const mesh::SurfaceMesh& tessellation,
                                       const optimize::CurveOptions& curve = {});

}  // namespace hexdom::cad
