// Subcommands of the hexdom program. Each file registers one subcommand on the CLI11 app; its
// callback parses nothing itself, calls one stage of the core and writes the result.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "hexdom/autopolycube/autopolycube.h"

namespace hexdom::cli {

void add_convert(CLI::App& app);
void add_remesh(CLI::App& app);
void add_quality(CLI::App& app);
void add_generate(CLI::App& app);
void add_improve(CLI::App& app);
void add_segmentation_commands(CLI::App& app);  // segment, check, polycube
void add_cad_commands(CLI::App& app);           // tessellate
void add_auto_commands(CLI::App& app);          // autopolycube, mesh

/// hexdom autopolycube and hexdom polycube --auto: input, outputs and options.
struct AutoPolycubeArgs {
  std::string in, out, patches, polycube;
  autopolycube::AutoPolycubeOptions opt;
};
/// --polycube-out, --size, --level and the repair/untangle limits.
void add_autopolycube_options(CLI::App& cmd, AutoPolycubeArgs& a);
/// Reads a.in (labels, or patches labelled by their nearest axis), builds the structure and writes
/// a.out, a.patches (and a.polycube); prints the summary.
void run_autopolycube(AutoPolycubeArgs& a);

/// Prints progress and warnings from the core's log callback on stderr.
void print_log(int level, const std::string& message);

}  // namespace hexdom::cli
