// `mbsopt gradcheck`: a design problem's functionals and their gradients by every method, compared.
#pragma once

#include <CLI/CLI.hpp>

namespace mbsopt {

void registerGradcheckCommand(CLI::App& app);

}  // namespace mbsopt
