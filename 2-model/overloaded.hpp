// The usual visitor helper for std::visit over several lambdas.
#pragma once

namespace mbsopt {
template <class... Ts> struct Overloaded : Ts... { using Ts::operator()...; };
// C++20 deduces this for aggregates; clang 14 (the sanitizer build) still needs the guide.
template <class... Ts> Overloaded(Ts...) -> Overloaded<Ts...>;
}  // namespace mbsopt
