// Planar pendulum chains of any length, open and closed into one loop: the scenes on which the
// benchmarks measure how the cost of the dynamics grows with the number of coordinates, and on
// which the tests check properties that must hold whatever the size.
#pragma once

#include "mbsopt/integrators/scene.hpp"

namespace mbsopt {

/// Planar pendulum chain of `links` revolute joints about z (links 0.5 m, 2 kg, gravity −y), a
/// spring-damper at each joint; starts bent at 0.3 rad per joint, at rest. h = 1 ms, 1 s.
Scene planarChainScene(int links);

/// The planar chain bent by 2/links rad per joint (2 rad in all, whatever N), its tip pinned where
/// it starts by a spherical cut to the ground: one loop, 3 closure equations of rank 2 (the z row is
/// identically zero in the plane), N − 2 degrees of freedom.
Scene closedPlanarChainScene(int links);

}  // namespace mbsopt
