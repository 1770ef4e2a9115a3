// The initial state of a design on closed loops. The scene's (q₀, q̇₀) close its loops at its own
// parameters; a geometric design variable (an offset's translation, isGeometricParameter) opens them
// again. They are closed along fixed directions, V₁, an orthonormal basis of the row space of B at
// the scene's own state and parameters (the directions of the scene's own minimum-norm assembly):
//   q₀(b) = q₀ + V₁ z,   b(q₀ + V₁ z; b) = 0;     q̇₀(b) = q̇₀ + V₁ w,   ḃ(q₀(b), q̇₀ + V₁ w; b) = 0.
// B V₁ has full column rank near the scene's state, so z and w are locally unique and smooth in b
// (implicit function theorem), with
//   B V₁ dz/db = −∂b/∂b,   B V₁ dw/db = −(∂ḃ/∂q V₁ dz/db + ∂ḃ/∂b)
// (TrajectoryDerivatives::initialSensitivities). Directions that moved with the design, as a fresh
// minimum-norm assembly's would, make the state depend on the path of the iterations, which no
// implicit function describes. Only a design with a variable that moves a loop closes it again
// (evaluateDesign); every other design starts from the scene's state, to the bit.
#pragma once

#include <Eigen/Core>

#include "mbsopt/integrators/scene.hpp"
#include "mbsopt/sensitivity/design_problem.hpp"

namespace mbsopt {

/// Whether some design variable moves a loop's closure (movesLoopClosure): then each design's
/// initial state is closed again (designInitialState).
bool designMovesLoopClosure(const DesignProblem& problem);

/// V₁ of the scene: free coordinates × the rank of B at (scene.q0, the scene's parameters), at the
/// integrator's SVD threshold.
Eigen::MatrixXd closingDirections(const Scene& scene);

/// The scene's initial state with `model` (the scene's model with a design applied), its loops closed
/// again along closingDirections(scene) (closeLoops, to 1e-12; where Gauss-Newton stagnates, as
/// assemble() does, to 1e-9). Throws AssemblyError (3-algorithms/assembly.hpp) naming the cut joints when
/// it cannot close them (a design whose loop cannot be assembled).
void designInitialState(const Scene& scene, const Model& model, Eigen::VectorXd& q, Eigen::VectorXd& v);

}  // namespace mbsopt
