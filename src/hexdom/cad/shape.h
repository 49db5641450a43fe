// A B-rep solid handed over from a CAD file or from FreeCAD, and what the later stages ask of it.
//
// Shape is an opaque handle: this header, like every public header of hexdom_cad, includes no
// OpenCASCADE, so the program, the Python module and builds without OCCT see the same API. As in
// Gmsh, every function exists without OCCT and then throws "built without OpenCASCADE: cannot ...".
//
// Numbering: faces, edges and vertices are numbered from 1 in the order of OCCT's
// TopExp::MapShapes(shape, TopAbs_FACE / EDGE / VERTEX), which is FreeCAD's Face1, Face2, ...
// (Edge1, ..., Vertex1, ...) for the same shape.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <memory>
#include <string>
#include <vector>

namespace hexdom::cad {

/// Geometric type of a face's underlying surface.
enum class SurfaceType { Plane, Cylinder, Cone, Sphere, Torus, BSpline, Bezier, Revolution, Extrusion, Offset, Other };

/// "plane", "cylinder", "cone", "sphere", "torus", "bspline", "bezier", "revolution", "extrusion",
/// "offset", "other".
std::string surface_type_name(SurfaceType type);

/// A B-rep solid (shared, immutable). A default-constructed Shape is empty.
class Shape {
 public:
  struct Impl;  ///< OCCT side, defined in cad/shape_impl.h
  Shape() = default;
  explicit Shape(std::shared_ptr<const Impl> impl) : impl_(std::move(impl)) {}
  bool is_empty() const { return !impl_; }
  const Impl& impl() const;  ///< throws GeometryError for an empty shape
  /// Where the shape came from ("part.step", "<BREP string>"), for messages.
  const std::string& source() const;

 private:
  std::shared_ptr<const Impl> impl_;
};

/// True when hexdom_cad was built with OpenCASCADE.
bool has_opencascade();

/// Counts of the shape's topology.
struct ShapeInfo {
  int faces = 0, edges = 0, vertices = 0, shells = 0;
  double volume = 0;              ///< signed (OCCT GProp); positive for a correctly oriented solid
  double area = 0;                ///< surface area
  Eigen::AlignedBox3d box;        ///< axis-aligned bounding box
  std::vector<SurfaceType> face_types;  ///< #faces, face_types[i] is Face{i+1}'s surface type
  Eigen::MatrixXd vertex_points;        ///< #vertices by 3, row i is Vertex{i+1}
};
ShapeInfo shape_info(const Shape& shape);

/// The numbers FreeCAD gives the solid's faces (`dim` 2), edges (1) or vertices (0) in the shape
/// the solid was read from: element i is Face{i+1}'s (Edge, Vertex) number in the whole file's or
/// BREP text's shape, a compound of several solids for instance (cad::read_solids). 1..n for a
/// solid that is its whole source. Throws std::invalid_argument for another `dim`.
std::vector<int> source_numbers(const Shape& shape, int dim);

/// Signed volume of the solid (OCCT GProp), as ShapeInfo::volume.
double shape_volume(const Shape& shape);

/// The shape in OCCT's BREP text format (what FreeCAD's shape.exportBrepToString() produces).
std::string write_brep_string(const Shape& shape);
/// Writes the shape as a .brep file (atomically: nothing is left at `path` on failure).
void write_brep(const Shape& shape, const std::string& path);

}  // namespace hexdom::cad
