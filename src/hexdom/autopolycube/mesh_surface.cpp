#include "hexdom/autopolycube/mesh_surface.h"

#include <chrono>
#include <cstdio>

#include "hexdom/generation/generate.h"

namespace hexdom::autopolycube {

namespace {
using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }
std::string fmt(const char* f, double a, double b = 0, double c = 0, double d = 0) {
  char buf[256];
  std::snprintf(buf, sizeof buf, f, a, b, c, d);
  return buf;
}
}  // namespace

MeshSurfaceRun mesh_surface(const mesh::SurfaceMesh& surface, const MeshSurfaceOptions& opt, MeshSurfaceRun* progress) {
  MeshSurfaceRun local;
  MeshSurfaceRun& r = progress ? *progress : local;
  r = MeshSurfaceRun{};
  auto say = [&](const std::string& m) { if (opt.log) opt.log(0, m); };
  const LogCallback inner = opt.verbose ? opt.log : LogCallback();
  const double diag = surface.V.rows() ? (surface.V.colwise().maxCoeff() - surface.V.colwise().minCoeff()).norm() : 0.0;
  const double size = opt.size > 0 ? opt.size : diag / 30.0;

  r.stage = "segment";
  auto t = Clock::now();
  segmentation::CvtOptions so = opt.segment;
  so.log = inner;
  r.labels = surface;
  r.labels.patch = segmentation::segment_cvt(surface, so).label;
  r.seconds[0] = since(t);
  say(fmt("segment: %.0f triangles labelled in %.2f s", static_cast<double>(surface.F.rows()), r.seconds[0]));

  r.stage = "autopolycube";
  t = Clock::now();
  AutoPolycubeOptions ao = opt.polycube;
  ao.size = size;
  ao.level = opt.level;
  ao.log = inner;
  autopolycube(r.labels, ao, &r.polycube);
  r.seconds[1] = since(t);
  say(fmt("autopolycube: %.0f charts (%.0f relabelled), %.0f blocks of %g", r.polycube.charts, r.polycube.relabelled,
          r.polycube.blocks, r.polycube.cell) +
      fmt(", worst block SJ %.3f, in %.2f s", r.polycube.min_block_quality, r.seconds[1]));

  r.stage = "generate";
  t = Clock::now();
  generation::GenerateOptions go;
  go.level = opt.level;
  go.relax_sweeps = opt.relax_sweeps;
  go.log = inner;
  r.generated = generation::generate(r.polycube.patches, r.polycube.structure, go);
  r.generated_quality = quality::quality_report(r.generated);
  r.seconds[2] = since(t);
  say(fmt("generate: %.0f cells, worst hex SJ %.3f, %.0f inverted, in %.2f s", r.generated.num_cells(),
          r.generated_quality.hex.sj_min, r.generated_quality.hex.inverted, r.seconds[2]));

  r.stage = "improve";
  t = Clock::now();
  if (opt.improve) {
    quality::ImproveOptions io = opt.improvement;
    io.surface = r.polycube.patches;
    io.log = inner;
    quality::ImproveResult ir = quality::improve(r.generated, io);
    r.mesh = std::move(ir.mesh);
    r.quality = ir.after;
  } else {
    r.mesh = r.generated;
    r.quality = r.generated_quality;
  }
  r.seconds[3] = since(t);
  const int inverted = r.quality.hex.inverted + r.quality.prism.inverted + r.quality.tet.inverted;
  say(fmt("improve: %.0f cells, worst hex SJ %.3f, mean %.3f, %.0f inverted", r.mesh.num_cells(), r.quality.hex.sj_min,
          r.quality.hex.sj_mean, inverted) +
      fmt(", in %.2f s", r.seconds[3]));
  r.stage = "done";
  return progress ? *progress : local;
}

std::string to_text(const MeshSurfaceRun& r) {
  std::string s;
  s += fmt("segment       %8.2f s\n", r.seconds[0]);
  s += fmt("autopolycube  %8.2f s  %5.0f charts, %5.0f blocks, h = %g\n", r.seconds[1], r.polycube.charts, r.polycube.blocks,
           r.polycube.cell);
  s += fmt("generate      %8.2f s  %8.0f cells\n", r.seconds[2], r.generated.num_cells());
  s += fmt("improve       %8.2f s  %8.0f cells\n", r.seconds[3], r.mesh.num_cells());
  return s;
}

}  // namespace hexdom::autopolycube
