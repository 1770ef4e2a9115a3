// mbsopt: optimal design of multibody systems from the command line.
#include <CLI/CLI.hpp>
#include <exception>
#include <iostream>
#include <string>
#include <vector>

#include "mbsopt/io/scene_file.hpp"
#include "mbsopt/design/provenance.hpp"
#include "app/benchmark_command.hpp"
#include "app/compare_command.hpp"
#include "app/exit_status.hpp"
#include "app/gradcheck_command.hpp"
#include "app/optimize_command.hpp"
#include "app/parameters_command.hpp"
#include "app/precision_command.hpp"
#include "app/simulate_command.hpp"

int main(int argc, char** argv) {
  CLI::App app{
      "mbsopt - simulate multibody systems described in scene files (Newmark, relative coordinates, closed loops by "
      "SVD), compute exact design gradients and optimise designs"};
  app.set_version_flag("--version", std::string("mbsopt ") + mbsopt::version());
  app.require_subcommand(1);
  mbsopt::recordCommandLine(argc, argv);
  mbsopt::registerSimulateCommand(app);
  mbsopt::registerParametersCommand(app);
  mbsopt::registerGradcheckCommand(app);
  mbsopt::registerOptimizeCommand(app);
  mbsopt::registerCompareCommand(app);
  mbsopt::registerBenchmarkCommand(app);
  mbsopt::registerPrecisionCommand(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
    // One line in the program's own words, and the documented exit status of an error.
    const std::vector<CLI::App*> chosen = app.get_subcommands();
    const std::string command = chosen.empty() ? "" : chosen.front()->get_name();
    std::string message = e.what();
    if (dynamic_cast<const CLI::ExtrasError*>(&e) != nullptr) {  // CLI11 lists them in reverse order
      std::vector<std::string> extras = chosen.empty() ? app.remaining() : chosen.front()->remaining();
      if (extras.empty()) extras = app.remaining();
      if (!extras.empty())
        message = extras.front().starts_with('-') ? (command.empty() ? "mbsopt" : command) + " has no option " + extras.front()
                                                  : (command.empty() ? "mbsopt" : command) + " takes no argument '" +
                                                        extras.front() + "'";
    }
    std::cerr << "mbsopt: error: " << message << " (mbsopt " << (command.empty() ? "" : command + " ")
              << "--help lists the options)\n";
    return 1;
  } catch (const mbsopt::NotConverged& e) {  // the outputs are written; the summary said why
    std::cerr << "mbsopt: " << e.what() << '\n';
    return mbsopt::kExitNotConverged;
  } catch (const mbsopt::SceneError& e) {  // "file:line:column: error: what", one line
    std::cerr << e.what() << '\n';
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "mbsopt: error: " << e.what() << '\n';
    return 1;
  }
  return 0;
}
