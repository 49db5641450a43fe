#include "hexdom/pipeline/stretch.h"

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

void map_run(MeshSurfaceRun& r, const Stretch& s, bool forward) {
  auto map = [&](Eigen::MatrixXd& V) { V = forward ? stretched(V, s) : unstretched(V, s); };
  for (Eigen::MatrixXd* V : {&r.mesh.V, &r.generated.V, &r.labels.V, &r.polycube.structure.V, &r.polycube.patches.V,
                             &r.polycube.labels.V, &r.polycube.polycube.V})
    map(*V);
  if (r.mesh.num_cells() > 0) r.quality = quality::quality_report(r.mesh);
  if (r.generated.num_cells() > 0) r.generated_quality = quality::quality_report(r.generated);
}

}  // namespace hexdom::pipeline
