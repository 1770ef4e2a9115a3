// MuJoCo's side of the peer comparison (peer_comparison.cpp): a PinTree written as MJCF and compiled by
// MuJoCo 2.2.2 (Debian's libmujoco-dev), run with its own integrators at fixed steps.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "bench/peer/simbody_models.hpp"

namespace peer {

enum class MujocoIntegrator { Euler, Implicit, RK4 };
const char* integratorName(MujocoIntegrator integrator);

struct MujocoRun {
  bool ok = false;
  std::string message;                       ///< why it failed (a non-finite state, MuJoCo's warning)
  std::vector<std::vector<double>> outputs;  ///< the pin angles at each output time
  double seconds = 0.0;                      ///< wall time of the steps
  long steps = 0;
};

/// A PinTree in MuJoCo: a body per pin, a hinge about z at its location, the bar's inertia; each
/// closure an equality `connect` (MuJoCo's constraints are soft: solref's time constant, which MuJoCo
/// keeps at least twice the step, sets how far the loop opens); gravity.
class MujocoModel {
 public:
  ~MujocoModel();
  MujocoModel(const MujocoModel&) = delete;
  MujocoModel& operator=(const MujocoModel&) = delete;

  /// Null, with `why` set, for a tree MuJoCo cannot take as such here (springs, torques).
  static std::unique_ptr<MujocoModel> pinTree(const PinTree& tree, std::string& why);
  /// A model file, MuJoCo's `disable_flags` set (mjDSBL_CONTACT, …), started at rest but for the
  /// joints of `rates` [rad/s]; its outputs are the angles of the hinges `joints` from their qpos0.
  static std::unique_ptr<MujocoModel> file(const std::string& path, int disable_flags,
                                           const std::vector<std::string>& joints,
                                           const std::vector<std::pair<std::string, double>>& rates);

  /// The MJCF it compiled (for the record; a model file's path).
  const std::string& mjcf() const;
  /// From the tree's initial state to each output time (whole numbers of steps of `step` between
  /// them); fails when the state stops being finite or MuJoCo warns of instability.
  MujocoRun run(MujocoIntegrator integrator, double step, const std::vector<double>& output_times) const;

 private:
  MujocoModel();
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// "2.2.2" (mj_versionString).
std::string mujocoVersion();

}  // namespace peer
