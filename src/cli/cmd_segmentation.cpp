#include "commands.h"

namespace hexdom::cli {
void add_segmentation_commands(CLI::App& /*app*/) {}
}  // namespace hexdom::cli
