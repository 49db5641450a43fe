// hexdom: the command-line program. Exit codes: 0 success; 1 bad input or geometry; 2 usage;
// 3 a meshing stage could not keep its contract; 4 internal error; 5 a time budget passed before
// there was a result (hexdom mesh --method polycube --polycube-seconds S); 130 stopped by Ctrl-C
// (SIGINT) or SIGTERM: the running stage ends within a fraction of a second and no file is
// written; a second Ctrl-C kills the program at once.
#include <csignal>
#include <iostream>

#include "commands.h"
#include "hexdom/common/error.h"
#include "hexdom/common/interrupt.h"

namespace {
const hexdom::Interrupt interrupt;  // raised by Ctrl-C; every command runs under it

extern "C" void on_signal(int sig) {
  interrupt.raise();
  std::signal(sig, SIG_DFL);  // the next one kills
}
}  // namespace

namespace hexdom::cli {
void print_log(int level, const std::string& message) {
  std::cerr << (level > 0 ? "hexdom: warning: " : "hexdom: ") << message << std::endl;
}
}  // namespace hexdom::cli

int main(int argc, char** argv) {
  CLI::App app{"HexDom: hex-dominant volume meshes from polycube structures"};
  app.set_version_flag("--version", std::string("hexdom ") + HEXDOM_VERSION);
  app.require_subcommand(1);
  hexdom::cli::add_convert(app);
  hexdom::cli::add_remesh(app);
  hexdom::cli::add_quality(app);
  hexdom::cli::add_generate(app);
  hexdom::cli::add_improve(app);
  hexdom::cli::add_segmentation_commands(app);
  hexdom::cli::add_cad_commands(app);
  hexdom::cli::add_auto_commands(app);
  const hexdom::InterruptScope scope(&interrupt);
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  try {
    app.parse(argc, argv);
  } catch (const hexdom::InterruptedError& e) {
    std::cerr << "hexdom: stopped (" << e.what() << "); nothing written" << std::endl;
    return 130;
  } catch (const CLI::ParseError& e) {
    // --help and --version exit 0; usage errors exit 2 (CLI11's own codes are 105-109).
    return app.exit(e) == 0 ? 0 : 2;
  } catch (const hexdom::InputError& e) {
    std::cerr << "hexdom: error: " << e.what() << std::endl;
    return 1;
  } catch (const hexdom::GeometryError& e) {
    std::cerr << "hexdom: error: " << e.what() << std::endl;
    return 1;
  } catch (const hexdom::MeshingError& e) {
    std::cerr << "hexdom: error: " << e.what() << std::endl;
    return 3;
  } catch (const hexdom::TimeoutError& e) {
    std::cerr << "hexdom: error: " << e.what() << std::endl;
    return 5;
  } catch (const std::exception& e) {
    std::cerr << "hexdom: error: internal error: " << e.what() << std::endl;
    return 4;
  }
  return 0;
}
