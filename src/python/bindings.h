// Each stage's Python bindings live in their own bind_<stage>.cpp and are registered here.
#pragma once

#include <pybind11/pybind11.h>

#include <Eigen/Core>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "hexdom/common/error.h"
#include "hexdom/pipeline/mesh_surface.h"
#include "hexdom/pipeline/stretch.h"

namespace hexdom::python {
/// A MeshSurfaceRun as _hexdom.mesh_surface returns it (bind_auto.cpp); also mesh_cad's "run".
pybind11::dict run_dict(const pipeline::MeshSurfaceRun& r);
/// The MeshSurfaceOptions of mesh_surface's and mesh_cad's keyword arguments (bind_auto.cpp).
/// polycube_seconds: None keeps the default budget (auto: MeshSurfaceOptions::polycube_seconds;
/// polycube: none); a number sets it, and with method "polycube" the deadline from now.
/// face_sizes: cell size per face number (overlay::LocalSize), checked against the part later.
/// time_limit: seconds the whole call may take (MeshSurfaceOptions::time_limit; 0: no limit).
/// pillow_curves: overlay::OverlayOptions::pillow_curves.
pipeline::MeshSurfaceOptions mesh_surface_options(double size, int level, double edge_weight, int max_relabels,
                                                      int relax_sweeps, bool improve, bool align,
                                                      const std::optional<Eigen::Matrix3d>& frame,
                                                  const std::string& method = "auto",
                                                  std::optional<double> polycube_seconds = std::nullopt,
                                                  double max_size = 0, double min_size = 0, double cells_across = 2,
                                                  const std::map<int, double>& face_sizes = {},
                                                  double growth_rate = overlay::kGrowthRate, int order = 1,
                                                  double time_limit = 0, bool pillow_curves = false);
/// The stretch a stage's `frame` and `stretch` keywords name (stretch: the factors along the
/// frame's axes, MeshSurfaceRun::stretch; frame none: the model's axes); none when stretch is none
/// or all ones. InputError for a frame that is not a rotation or a factor not positive.
std::optional<pipeline::Stretch> stretch_arg(const std::optional<Eigen::Matrix3d>& frame,
                                             const std::optional<Eigen::Vector3d>& stretch);
/// A stage's input `s` taken into the stretched frame the `frame` and `stretch` keywords name
/// (stretch_arg), and `R`, the frame the stage then works in, set to the identity; returns that
/// stretch, to map the results back (none: `s` and `R` left as they are).
std::optional<pipeline::Stretch> into_stretched_frame(mesh::SurfaceMesh& s, Eigen::Matrix3d& R,
                                                      const std::optional<Eigen::Matrix3d>& frame,
                                                      const std::optional<Eigen::Vector3d>& stretch);
/// Raises `e` as the _hexdom error of its class (module: _hexdom) with attribute `name` set to
/// `value` (what the finished stages made, for a front end that shows them).
[[noreturn]] void raise_with(pybind11::handle module, const Error& e, const char* name, pybind11::object value);
/// The warnings (log level 1 and above) a core call says, in the order said; the log callback
/// may be called from several threads.
class Warnings {
 public:
  LogCallback callback();
  std::vector<std::string> lines() const;

 private:
  mutable std::mutex mutex_;
  std::vector<std::string> lines_;
};
/// The text of the polycube_seconds= keyword's documentation, shared by mesh_surface and mesh_cad.
extern const char* const kPolycubeSecondsDoc;
extern const char* const kSizeBoundsDoc;
/// The figures of a second-order mesh's making, as _hexdom's dicts hold them.
pybind11::dict second_order_dict(const optimize::SecondOrderReport& report);
/// The order= keyword's documentation, shared by mesh_surface and mesh_cad.
extern const char* const kOrderDoc;
/// The time_limit= keyword's documentation, shared by mesh_surface and mesh_cad.
extern const char* const kTimeLimitDoc;
extern const char* const kPillowCurvesDoc;
void bind_segmentation(pybind11::module_& m);
void bind_polycube(pybind11::module_& m);
void bind_cad(pybind11::module_& m);
void bind_auto(pybind11::module_& m);
void bind_labels(pybind11::module_& m);
}  // namespace hexdom::python
