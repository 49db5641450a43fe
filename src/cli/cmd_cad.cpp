#include "commands.h"

namespace hexdom::cli {
void add_cad_commands(CLI::App& /*app*/) {}
}  // namespace hexdom::cli
