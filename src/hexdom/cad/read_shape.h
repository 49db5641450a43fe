// Reading one solid from a STEP, IGES or BREP file, or from a BREP string (FreeCAD hands a shape
// over as shape.exportBrepToString()).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "hexdom/cad/shape.h"
#include "hexdom/common/error.h"

namespace hexdom::cad {

struct ReadOptions {
  /// Which solid to take (1-based, in TopExp::MapShapes(shape, TopAbs_SOLID) order) when the file
  /// holds several; a file with several solids and no choice uses solid 1 and logs a warning.
  int solid = 0;
  LogCallback log;  ///< warnings (several solids, an invalid B-rep that was read anyway)
};

/// Reads a .step/.stp, .iges/.igs or .brep/.brp file (chosen by extension) and returns one solid.
/// Throws InputError ("part.step: ...") for a missing, unreadable or corrupt file, an unknown
/// extension or a solid index out of range; GeometryError for a file that holds no solid (only
/// shells, faces or wires: the message says which) or whose solid is open or non-manifold (naming
/// the edge and its faces).
Shape read_shape(const std::string& path, const ReadOptions& options = {});

/// Same for a shape in OCCT's BREP text format; messages name the source as "<BREP string>".
Shape read_brep_string(const std::string& brep, const ReadOptions& options = {});

/// Every solid of a CAD file or BREP text (as read_shape_or_brep), in TopExp::MapShapes order,
/// each checked as read_shape checks its one; only solid options.solid when it is given. A file
/// with one solid gives one. Solids of a source with several keep the source's numbers of their
/// faces, edges and vertices (source_numbers), the chosen one too. Throws as read_shape.
std::vector<Shape> read_solids(const std::string& source, const ReadOptions& options = {});

/// The pairs (1-based, first < second) of `solids` that touch or overlap: closer than
/// `relative_tolerance` times the largest bounding-box diagonal among them (BRepExtrema distance 0
/// for solids that overlap or share a face). Meshing them one by one gives meshes that do not
/// conform where they touch.
std::vector<std::array<int, 2>> touching_solids(const std::vector<Shape>& solids, double relative_tolerance);

/// True when `text` looks like BREP text rather than a file name (it holds "CASCADE Topology").
bool is_brep_string(const std::string& text);

/// read_brep_string(source) when is_brep_string(source), else read_shape(source).
Shape read_shape_or_brep(const std::string& source, const ReadOptions& options = {});

}  // namespace hexdom::cad
