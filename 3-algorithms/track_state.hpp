// A model's track at a curve slider's arc length, in the scalar of the recursions.
#pragma once

#include "mbsopt/model/model.hpp"
#include "mbsopt/model/workspace.hpp"

namespace mbsopt {

/// Whether ws.parameter_seeds names one of the track's numbers (never in double).
template <class Scalar>
bool seedsTrack(const Model& model, const Workspace<Scalar>& ws, TrackIndex track) {
  if constexpr (std::is_same_v<Scalar, double>) {
    return false;
  } else {
    for (const auto& [seeded, direction] : ws.parameter_seeds)
      if (trackOf(model, seeded) == static_cast<int>(track)) return true;
    return false;
  }
}

/// The geometry of track `track` at arc length s: exact at the value of s and to first order in s
/// (trackStateAt). In a pass seeded in one of the track's numbers, evaluated afresh from its numbers
/// read as parameters (trackPointAt), so it also carries ∂r/∂b, ∂ψ/∂b, ∂κ/∂b and ∂κ'/∂b.
template <class Scalar>
TrackPointTpl<Scalar> trackAt(const Model& model, const Workspace<Scalar>& ws, TrackIndex track, const Scalar& s) {
  if (!seedsTrack(model, ws, track)) return trackStateAt(model.track(track), s);
  const ModelTrack& described = model.tracks()[static_cast<std::size_t>(track)];
  TrackNumbersTpl<Scalar> numbers;
  numbers.origin = parameter(model, ws, described.origin);
  numbers.heading = parameter(model, ws, described.heading);
  numbers.types = described.geometry.numbers().types;
  for (std::size_t k = 0; k < numbers.types.size(); ++k) {
    std::array<Scalar, 2> written{Scalar(0), Scalar(0)};
    for (int n = 0; n < numberCount(numbers.types[k]); ++n)
      written[static_cast<std::size_t>(n)] = parameter(model, ws, described.segments[k][static_cast<std::size_t>(n)]);
    numbers.numbers.push_back(written);
  }
  return trackPointAt(numbers, s);
}

}  // namespace mbsopt
