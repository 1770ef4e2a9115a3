// The usual visitor helper for std::visit over several lambdas.
#pragma once

namespace mbsopt {
template <class... Ts> struct Overloaded : Ts... { using Ts::operator()...; };
}  // namespace mbsopt
