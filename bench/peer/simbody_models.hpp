// The Simbody side of the peer comparison: the benchmark mechanisms built with Simbody's
// MobilizedBody::Pin and Constraint::PointInPlane (springs and torques as Simbody's force elements),
// and one timed run with a Simbody integrator.
//
// Simbody 3.7's headers do not compile as C++20 (ambiguous reversed operator== in ContactGeometry.h),
// so this interface uses standard types only and simbody_models.cpp is compiled as C++17.
#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

namespace peer {

/// A rigid body attached to a pin's frame: mass, centre of mass in the frame, principal moments of
/// inertia about the centre of mass along the frame's axes.
struct Bar {
  double mass;
  std::array<double, 3> com;
  std::array<double, 3> inertia;
};

/// A point fixed in a pin's frame (`pin` indexes PinTree::pins; −1: the ground).
struct PinPoint {
  int pin;
  std::array<double, 3> point;
};

/// A planar mechanism of pins about z, a tree from the ground closed by point coincidences, with linear
/// point-to-point springs and constant pin torques: what peer_comparison.cpp reads off an mbsopt model
/// made of revolute joints about z and offsets (Andrews' squeezer), so that the two cannot differ.
struct PinTree {
  struct Pin {
    int parent;                      ///< the parent pin, −1 for the ground
    std::array<double, 3> location;  ///< of the pin's axis in the parent's frame
    Bar bar;
    double q0, u0;  ///< initial angle (relative to the parent) and rate
  };
  struct Closure {  ///< the two points coincide (in the plane: two PointInPlane constraints)
    PinPoint a, b;
  };
  struct Spring {  ///< tension stiffness · (length − rest_length), along the line between the points
    PinPoint a, b;
    double stiffness, rest_length;
  };
  struct Torque {
    int pin;
    double value;
  };
  std::vector<Pin> pins;  ///< the coordinates, in the comparison's order
  std::vector<Closure> closures;
  std::vector<Spring> springs;
  std::vector<Torque> torques;
  std::array<double, 3> gravity{};
};

enum class SimbodyIntegrator { RungeKuttaFeldberg, RungeKuttaMerson, CPodes };
const char* integratorName(SimbodyIntegrator integrator);

struct SimbodyRun {
  bool ok = false;
  std::string message;                       ///< why it failed
  std::vector<std::vector<double>> outputs;  ///< the pin angles at each output time
  double seconds = 0.0;                      ///< wall time of the integration (integrator creation to the end)
  long steps = 0, step_attempts = 0, realizations = 0, projections = 0;
};

/// A Simbody multibody system whose coordinates are pin angles, in the comparison's order.
class SimbodyModel {
 public:
  ~SimbodyModel();
  SimbodyModel(const SimbodyModel&) = delete;
  SimbodyModel& operator=(const SimbodyModel&) = delete;

  /// The four-bar of problems/scenes/four_bar.yaml: crank (A = origin, 0.4 m), coupler on the crank's
  /// tip (1 m), rocker (D = (1, 0), 0.8 m); the coupler's tip held on the rocker's tip by two
  /// PointInPlane constraints. Coordinates: crank, coupler (relative to the crank), rocker.
  static std::unique_ptr<SimbodyModel> fourBar(const Bar& crank, const Bar& coupler, const Bar& rocker);
  /// A chain of `links` pins about z, each link uniform along its x axis; horizontal, at rest.
  static std::unique_ptr<SimbodyModel> chain(int links, double length, double mass);
  /// The N four-bar of IFToMM A02: N+1 rockers pinned to the ground at x = 0, 1, …, N, N couplers,
  /// every bar 1 m, 1 kg, uniform; every rocker at `rocker_angle` from +x turning at `rocker_rate`, the
  /// couplers horizontal (A02 itself: π/2 and −1 rad/s, the tips moving at 1 m/s along +x).
  /// Coordinates: rockers 0..N, then couplers 0..N−1 (relative to their rocker).
  static std::unique_ptr<SimbodyModel> nFourBar(int n, double rocker_angle, double rocker_rate);

  /// Any PinTree. Throws when its initial angles leave a closure open by more than 1e-12 m: both engines
  /// must start from the same state, and Simbody's initialisation would project it onto the closure.
  static std::unique_ptr<SimbodyModel> pinTree(const PinTree& tree);

  int coordinateCount() const;
  /// Integrates from t = 0 to each output time in turn (no interpolated reports) at `accuracy`; fails
  /// (ok = false) when the integrator throws or ends the simulation, or after `max_seconds` of wall time.
  SimbodyRun run(SimbodyIntegrator integrator, double accuracy, const std::vector<double>& output_times,
                 double max_seconds) const;

 private:
  SimbodyModel();
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// "3.7" (the library's own version functions).
std::string simbodyVersion();

}  // namespace peer
