// mbsopt: optimal design of multibody systems from the command line.
#include <CLI/CLI.hpp>
#include <exception>
#include <iostream>

#include "app/simulate_command.hpp"

int main(int argc, char** argv) {
  CLI::App app{"mbsopt - simulate multibody systems (Newmark, relative coordinates, closed loops by SVD)"};
  app.require_subcommand(1);
  mbsopt::registerSimulateCommand(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const std::exception& e) {
    std::cerr << "mbsopt: error: " << e.what() << '\n';
    return 1;
  }
  return 0;
}
