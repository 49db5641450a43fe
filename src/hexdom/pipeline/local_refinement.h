// The polycube path's meshes where local sizes ask for smaller cells than its grid: the cell chosen
// for them, and the mesh refined by thirds near the faces (and polylines) that ask; and how any
// mesh meets the local sizes (the automatic choice between the paths weighs it).
#pragma once

#include <string>
#include <vector>

#include "hexdom/mesh/mesh.h"
#include "hexdom/overlay/local_size.h"
#include "hexdom/pipeline/mesh_surface.h"

namespace hexdom::pipeline {

/// The polycube's cell for the default or asked `size` when `field` (opt.overlay.local_sizes on the
/// surface meshed) has sizes: made such that some level by thirds lands within 1.2 of the smallest
/// (overlay::local_levels, as the overlay's grid is made); `size` otherwise. Says so in the log.
double cell_for_local_sizes(const overlay::LocalSizeField& field, double size, const MeshSurfaceOptions& opt);

/// The generated mesh `generated` (before its improvement: no pillow layer yet) refined where `field`
/// (opt.overlay.local_sizes on the surface meshed, in the mesh's space; real lengths measured
/// through opt.stretched_by) asks for smaller cells: a hexahedron is split in 27 where the
/// overlay's octree would split a cell of its box and mean edge (overlay::LocalSizeField::split),
/// its neighbours get the transition templates (mesh::refine_by_thirds); again on the cubes of the
/// split cells (never on a template's piece), up to 4 levels; the new boundary nodes put on the
/// nearest point of `patches` (they lie on the coarse cells' faces). The improvement that follows
/// (pillow layer included) then works on the refined cells. Nothing changes when no size applies
/// or no cell asks; prisms and tetrahedra are not cut. Says what it did in the log.
void refine_to_local_sizes(const overlay::LocalSizeField& field, const mesh::SurfaceMesh& patches,
                           const MeshSurfaceOptions& opt, mesh::Mesh& generated);

/// How `mesh` meets `sizes` on `surface` (the surface it was made from; its patches are the faces
/// the sizes name). A size on a patch: the boundary faces whose centre is nearest a triangle of the
/// patch, each measured by its mean edge. A size along a polyline: the boundary edges whose ends and
/// midpoint lie within a tenth of the size of it, by their length. Each ratio is the median of
/// those over the size (0 when none lies there); met when within 20% of 1.
LocalSizeFit local_size_fit(const mesh::Mesh& mesh, const mesh::SurfaceMesh& surface,
                            const std::vector<overlay::LocalSize>& sizes);

/// "local sizes: cells 0.87 of the size on Face10 (1 of 1 within 20%)"-style line.
std::string local_fit_text(const LocalSizeFit& fit, const std::vector<overlay::LocalSize>& sizes);

}  // namespace hexdom::pipeline
