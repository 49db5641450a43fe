// Internal to the pipeline: a part thin along an axis of its frame (a plate, a rod) meshed by the
// polycube path with cells of a different length along each axis, by meshing it stretched along
// its thin axes and mapping the results back.
#pragma once

#include <Eigen/Core>
#include <optional>

#include "hexdom/mesh/mesh.h"
#include "hexdom/pipeline/mesh_surface.h"

namespace hexdom::pipeline {

/// x_stretched = factor .* (rotation * x): rotation takes the model to the part's frame.
struct Stretch {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d factor = Eigen::Vector3d::Ones();  ///< >= 1 per frame axis
  Eigen::Vector3d spacing = Eigen::Vector3d::Zero(); ///< the cell length per frame axis
  double size = 0;  ///< the element size in stretched space: spacing's largest
  double across = 0;  ///< cells across the part's thinnest extent (extent / spacing), fewest over the axes
};

/// The stretch that gives `surface` (in the frame `rotation` takes it to) cells of
/// overlay::grid_spacing(extent, size, across, max_cell_ratio, min_size) per frame axis: at least
/// `across` across each extent (none shorter than min_size when > 0), none longer than
/// max_cell_ratio times the shortest. None when across <= 0
/// or the shortest spacing is at least size / max_cell_ratio (the polycube's cubic cells, `across`
/// across a part one block thick, are then within max_cell_ratio to 1).
std::optional<Stretch> thin_stretch(const mesh::SurfaceMesh& surface, const Eigen::Matrix3d& rotation, double size,
                                    double across, double max_cell_ratio, double min_size = 0);

/// Rows of V (#V by 3) taken into stretched space, and back.
Eigen::MatrixXd stretched(const Eigen::MatrixXd& V, const Stretch& s);
Eigen::MatrixXd unstretched(const Eigen::MatrixXd& V, const Stretch& s);

/// The stretch by `factor` along the axes of `rotation` (spacing and size left unset): the one a run
/// reports (MeshSurfaceRun::frame's rotation and ::stretch), to redo a stage of it in the space it
/// ran in. InputError unless every factor is finite and positive.
Stretch stretch_of(const Eigen::Matrix3d& rotation, const Eigen::Vector3d& factor);

/// An automatic polycube's geometries (structure, patch surface, labels, polycube surface) taken
/// into stretched space (`forward`) or back.
void map_polycube(autopolycube::AutoPolycube& p, const Stretch& s, bool forward);

/// generate_and_improve on a polycube structure and its patch surface given in the model, for a
/// part the polycube path meshed stretched by `s`: both taken into stretched space and meshed there,
/// as mesh_surface meshes them, and the run mapped back (map_run). Given the structure and patch
/// surface a run of mesh_surface reports (and its frame's rotation and stretch, exactly), its mesh
/// bit for bit (MeshSurfaceOptions::stretched_by).
void generate_and_improve_stretched(const mesh::SurfaceMesh& patches, const mesh::Mesh& structure, const Stretch& s,
                                    const MeshSurfaceOptions& options, MeshSurfaceRun& r);

/// Every geometry of a run (mesh, generated, labels, the polycube's structure, patches, labels and
/// polycube; not the repaired labelling, which stays in stretched space for the candidates handed
/// it) taken into stretched space (`forward`) or back, and its quality reports measured again there.
void map_run(MeshSurfaceRun& run, const Stretch& s, bool forward);

}  // namespace hexdom::pipeline
