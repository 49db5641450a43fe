// OCCT side of cad::Shape. Internal to hexdom_cad: only cad/*.cpp include it.
#pragma once

#include <Geom_Curve.hxx>
#include <Standard_Failure.hxx>
#include <gp_Pnt.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS_Shape.hxx>

#include <string>
#include <vector>

#include "hexdom/cad/shape.h"

namespace hexdom::cad {

struct Shape::Impl {
  TopoDS_Shape shape;                 ///< one solid
  std::string source;                 ///< file name or "<BREP string>", for messages
  TopTools_IndexedMapOfShape faces;   ///< TopExp::MapShapes order: index i is Face{i}
  TopTools_IndexedMapOfShape edges;
  TopTools_IndexedMapOfShape vertices;
  /// When the solid is one of several in its source: the source shape's numbers (TopExp::MapShapes
  /// of the whole shape) of faces[i], edges[i], vertices[i]; empty when the solid is the whole source.
  std::vector<int> source_faces, source_edges, source_vertices;
};

/// Wraps a solid, filling the maps.
Shape make_shape(const TopoDS_Shape& solid, const std::string& source);

/// Nearest point of a curve within [first, last], ends included: point q, parameter t, distance d.
/// False when OCCT finds nothing (a null curve).
bool nearest_on_curve(const Handle(Geom_Curve)& curve, double first, double last, const gp_Pnt& p, gp_Pnt& q,
                      double& t, double& d);

/// Text of an OCCT exception ("Standard_ConstructionError: ...").
std::string occt_message(const Standard_Failure& e);

}  // namespace hexdom::cad
