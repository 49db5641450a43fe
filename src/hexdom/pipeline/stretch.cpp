#include "hexdom/pipeline/stretch.h"

#include "hexdom/common/error.h"
#include "hexdom/common/format.h"
#include "hexdom/overlay/grid.h"
#include "hexdom/quality/report.h"

namespace hexdom::pipeline {

std::optional<Stretch> thin_stretch(const mesh::SurfaceMesh& surface, const Eigen::Matrix3d& rotation, double size,
                                    double across, double max_cell_ratio, double min_size) {
  if (across <= 0 || size <= 0 || surface.V.rows() == 0) return std::nullopt;
  const Eigen::MatrixXd F = surface.V * rotation.transpose();
  const Eigen::Vector3d extent = (F.colwise().maxCoeff() - F.colwise().minCoeff()).transpose();
  Stretch s;
  s.rotation = rotation;
  s.spacing = overlay::grid_spacing(extent, size, across, max_cell_ratio, min_size);
  // Cubic cells of `size` already have `across` cells across an extent of across x size or more (the
  // polycube gives a thinner part one block, across cells): stretched only where those would be
  // needles, more than max_cell_ratio to 1.
  if (s.spacing.minCoeff() <= 0 || size <= max_cell_ratio * s.spacing.minCoeff() * (1 + 1e-9)) return std::nullopt;
  s.size = s.spacing.maxCoeff();
  s.across = extent.cwiseQuotient(s.spacing).minCoeff();
  for (int a = 0; a < 3; ++a) s.factor(a) = s.size / s.spacing(a);
  return s;
}

Eigen::MatrixXd stretched(const Eigen::MatrixXd& V, const Stretch& s) {
  if (V.rows() == 0) return V;
  return (V * s.rotation.transpose()) * s.factor.asDiagonal();
}

Eigen::MatrixXd unstretched(const Eigen::MatrixXd& V, const Stretch& s) {
  if (V.rows() == 0) return V;
  return (V * s.factor.cwiseInverse().asDiagonal()) * s.rotation;
}

Stretch stretch_of(const Eigen::Matrix3d& rotation, const Eigen::Vector3d& factor) {
  if (!factor.allFinite() || factor.minCoeff() <= 0)
    throw InputError(fmt("stretch (%g, %g, %g): each factor must be finite and positive", factor(0), factor(1), factor(2)));
  Stretch s;
  s.rotation = rotation;
  s.factor = factor;
  return s;
}

void map_polycube(autopolycube::AutoPolycube& p, const Stretch& s, bool forward) {
  for (Eigen::MatrixXd* V : {&p.structure.V, &p.patches.V, &p.labels.V, &p.polycube.V})
    *V = forward ? stretched(*V, s) : unstretched(*V, s);
}

void generate_and_improve_stretched(const mesh::SurfaceMesh& patches, const mesh::Mesh& structure, const Stretch& s,
                                    const MeshSurfaceOptions& options, MeshSurfaceRun& r) {
  mesh::SurfaceMesh sp = patches;
  sp.V = stretched(patches.V, s);
  mesh::Mesh ss = structure;
  ss.V = stretched(structure.V, s);
  try {
    generate_and_improve(sp, ss, options, r);
  } catch (...) {
    map_run(r, s, false);
    throw;
  }
  map_run(r, s, false);
}

void map_run(MeshSurfaceRun& r, const Stretch& s, bool forward) {
  auto map = [&](Eigen::MatrixXd& V) { V = forward ? stretched(V, s) : unstretched(V, s); };
  for (Eigen::MatrixXd* V : {&r.mesh.V, &r.generated.V, &r.labels.V}) map(*V);
  map_polycube(r.polycube, s, forward);
  if (r.mesh.num_cells() > 0) r.quality = quality::quality_report(r.mesh);
  if (r.generated.num_cells() > 0) r.generated_quality = quality::quality_report(r.generated);
}

}  // namespace hexdom::pipeline
