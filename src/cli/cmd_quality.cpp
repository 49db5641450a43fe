#include <iostream>

#include "commands.h"
#include "hexdom/io/mesh_io.h"
#include "hexdom/quality/report.h"

namespace hexdom::cli {

void add_quality(CLI::App& app) {
  auto* cmd = app.add_subcommand("quality", "Scaled Jacobian, edge ratio and inverted count per cell type");
  auto in = std::make_shared<std::string>();
  auto json = std::make_shared<bool>(false);
  cmd->add_option("-i,--input", *in, "volume mesh (.k, .vtk, .msh; second order: .vtk, .msh)")->required();
  cmd->add_flag("--json", *json, "print JSON: keys hex, prism, tet with count, sj_min, sj_mean, inverted, edge_ratio_min, edge_ratio_max; order; for a second-order mesh hex20, wedge15, tet10 with count, sj_min, inverted, volume");
  cmd->callback([=] {
    mesh::Mesh m = io::read_mesh(*in);
    auto report = quality::quality_report(m);
    if (*json) std::cout << quality::to_json(report) << std::endl;
    else std::cout << quality::to_text(report);
  });
}

}  // namespace hexdom::cli
