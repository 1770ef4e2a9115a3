// Side by side with peers: the same mechanisms in Simbody, MuJoCo and mbsopt, an agreement
// check at tight accuracy, and the engines' work-precision curves.
//
//   peer_comparison --out DIR [--quick] [--mechanisms four_bar,chain8,nfourbar4,andrews,humanoid,nfourbar16,a02_singular]
//
// Mechanisms (allMechanisms; all but nfourbar16 by default): the four-bar of problems/scenes/four_bar.yaml,
// an 8-link pendulum chain, IFToMM A02's N four-bar with N = 4 (and 16), Andrews' squeezing mechanism of
// problems/scenes/hard/andrews_squeezer.yaml (the Simbody model read off the loaded scene: pinTreeOf),
// MuJoCo's sample humanoid (mbsopt and MuJoCo only, both reading the file);
// a02_singular is a survey of A02 as specified, without a reference. For each mechanism:
//   - reference: Simbody's RungeKuttaMerson at accuracy 1e-12 (RungeKuttaFeldberg, then CPodes, if it
//     fails); for MuJoCo's sample humanoid, which Simbody does not read, MuJoCo's RK4 at a tiny step; its agreement with the other two at 1e-12 and with mbsopt at two tiny steps (and their
//     Richardson extrapolation, the trapezoidal rule's error being even in h) is reported;
//   - error of a run: the largest absolute joint-angle error [rad] over every coordinate and every
//     output time (every 0.1 s; Andrews' squeezer, 0.03 s long, every 1 ms; the integrators step onto
//     them: no interpolated reports);
//   - Simbody: RungeKuttaFeldberg, RungeKuttaMerson, CPodes at accuracies 1e-2 … 1e-10; mbsopt:
//     Newmark (β = 1/4, γ = 1/2, the project's defaults otherwise) over a ladder of fixed steps, once
//     solving every step to the Newton tolerance and once with `simulate --fast-steps` (Newton stopped
//     at kNewtonTruncationFraction of the step's truncation error, SVDs started from the last step's), and
//     driven by accuracy (`mbsopt simulate --integrator extrapolation|adaptive --accuracy TOL`) at
//     Simbody's accuracies taken as absolute tolerances on the angles (the adaptive Newmark down to
//     kAdaptiveDownTo), the error measured;
//   - MuJoCo (bench/peer/mujoco_models.hpp): the same pins as MJCF, Euler, implicit and RK4 over the
//     mbsopt ladder's fixed steps; a mechanism with springs or torques is not run there;
//   - time of a run: wall time of the integration only (integrator creation, initialisation and the
//     steps; the models are built beforehand), median of several repetitions;
//   - each engine's Pareto front (time against error), and the time ratio Simbody/mbsopt at errors
//     1e-3, 1e-5, 1e-7, interpolated log-log on each integrator's front (the fastest one wins).
// Failed runs (an mbsopt step whose Newton iteration does not converge, a Simbody exception) are
// kept in the data with their message and left out of the fronts.
//
// Writes DIR/peer_comparison.json, DIR/peer_comparison.md and, per mechanism,
// DIR/work_precision_<mechanism>.dat and .gp (scripts/peer_comparison.sh runs gnuplot on them).
#include <Eigen/Core>
#include <mujoco/mujoco.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iomanip>
#include <iostream>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <sstream>
#include <string>
#include <variant>
#include <vector>

#include "bench/peer/mujoco_models.hpp"
#include "bench/peer/simbody_models.hpp"
#include "mbsopt/model/model.hpp"
#include "mbsopt/integrators/integration.hpp"
#include "mbsopt/integrators/newmark.hpp"
#include "mbsopt/integrators/scene.hpp"
#include "mbsopt/io/scene_file.hpp"

// Which Simbody this was built against (bench/peer/CMakeLists.txt: Debian's package or a Release build).
#ifndef MBSOPT_PEER_SIMBODY_BUILD
#define MBSOPT_PEER_SIMBODY_BUILD "unknown Simbody build (MBSOPT_PEER_SIMBODY_BUILD not defined)"
#endif

namespace {

using Outputs = std::vector<std::vector<double>>;  // [output time][coordinate]
using nlohmann::json;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kAgreementThreshold = 1e-8;
constexpr double kReferenceBudget = 60.0;  ///< [s] of wall time for one Simbody run at 1e-12
constexpr double kRunBudget = 15.0;        ///< [s] for one Simbody run of the sweep (beyond: failed)
const std::vector<double> kTargetErrors = {1e-3, 1e-5, 1e-7};
constexpr double kAdaptiveDownTo = 1e-7;  ///< the adaptive Newmark's tightest accuracy in the sweep

// ---------------------------------------------------------------------------------------------
// Mechanisms

/// Debian's libmujoco-samples; its hinges compared, its throw (tests/7-io/test_model_file.cpp's).
constexpr const char* kHumanoidFile = "/usr/share/mujoco/model/humanoid/humanoid.xml";
const std::vector<std::string> kHumanoidHinges = {
    "abdomen_z",     "abdomen_y",       "abdomen_x",       "right_hip_x",   "right_hip_z",    "right_hip_y",
    "right_knee",    "right_ankle_y",   "right_ankle_x",   "left_hip_x",    "left_hip_z",     "left_hip_y",
    "left_knee",     "left_ankle_y",    "left_ankle_x",    "right_shoulder1", "right_shoulder2", "right_elbow",
    "left_shoulder1", "left_shoulder2", "left_elbow"};
const std::vector<std::pair<std::string, double>> kHumanoidThrow = {
    {"abdomen_z", 2.0}, {"right_hip_y", -4.0}, {"left_knee", 3.0}, {"right_shoulder1", 5.0}, {"left_elbow", -6.0}};

struct Mechanism {
  std::string key;
  std::string description;
  double end_time = 0.0;
  double output_interval = 0.1;
  std::vector<std::string> coordinates;  ///< mbsopt coordinate names, in Simbody's pin order
  std::function<mbsopt::Scene()> mbsopt_scene;
  std::function<std::unique_ptr<peer::SimbodyModel>()> simbody_model;  ///< empty: not in Simbody
  /// MuJoCo's model where it is not the pins of the mbsopt scene (pinTreeOf): a model file's.
  std::function<std::unique_ptr<peer::MujocoModel>()> mujoco_model;
  std::vector<int> ladder;       ///< mbsopt steps per output interval, coarse to fine
  std::vector<int> fine_ladder;  ///< two tiny steps (steps per interval) for the agreement check
  bool by_default = true;        ///< run without --mechanisms
};

std::array<double, 3> array3(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

peer::Bar barFrom(const mbsopt::Model& model, const mbsopt::Body& body) {
  if (!body.products_of_inertia.isZero(0.0))
    throw std::runtime_error("body '" + body.name + "': products of inertia are not supported here");
  return peer::Bar{model.value(body.mass), array3(model.centreOfMass(body)),
                   array3(model.vector(body.moments_of_inertia))};
}

peer::Bar barOf(const mbsopt::Model& model, const std::string& name) {
  for (const mbsopt::Body& body : model.bodies())
    if (body.name == name) return barFrom(model, body);
  throw std::runtime_error("no body '" + name + "' in the four-bar scene");
}

/// The scene a file describes, the loader's warnings on stderr.
mbsopt::Scene loaded(const mbsopt::SceneSource& source) {
  mbsopt::LoadedScene loaded = mbsopt::loadScene(source);
  for (const std::string& warning : loaded.warnings) std::cerr << source.path << ": " << warning << '\n';
  return std::move(loaded.scene);
}

mbsopt::Scene fourBarScene() {
  const std::optional<mbsopt::SceneSource> source = mbsopt::builtinScene("four_bar");
  if (!source) throw std::runtime_error("the built-in scene four_bar is missing");
  return loaded(*source);
}

/// problems/scenes/hard/andrews_squeezer.yaml, read from the source tree: the hard scenes are not
/// compiled in (problems/CMakeLists.txt takes problems/scenes/*.yaml only).
mbsopt::Scene andrewsScene() {
  return loaded(mbsopt::readSceneFile(std::string(MBSOPT_SOURCE_DIR) + "/problems/scenes/hard/andrews_squeezer.yaml"));
}

// ---- an mbsopt model of revolute joints about z and offsets, as Simbody's pins (peer::PinTree) ----

/// The point `point` of `frame` as a point of the pin whose frame carries it (the coordinate of the
/// nearest revolute joint towards the ground; −1: the ground); the offsets in between must only translate.
peer::PinPoint pinPoint(const mbsopt::Model& model, mbsopt::FrameIndex frame, Eigen::Vector3d point) {
  for (;;) {
    const int e = model.frames()[static_cast<std::size_t>(frame)].element;
    if (e < 0) return {-1, array3(point)};
    const mbsopt::KinematicElement& element = model.elements()[static_cast<std::size_t>(e)];
    if (std::holds_alternative<mbsopt::RevoluteJoint>(element.kind)) return {element.coordinate, array3(point)};
    const auto* offset = std::get_if<mbsopt::Offset>(&element.kind);
    if (!offset || offset->rotates)
      throw std::runtime_error("element '" + element.name + "': only revolute joints and translating offsets here");
    point += model.vector(offset->translation);
    frame = element.entry;
  }
}

/// The one body on a joint's frame.
peer::Bar barOn(const mbsopt::Model& model, mbsopt::FrameIndex frame) {
  const auto on = [&](const mbsopt::Body& body) { return body.frame == frame; };
  if (std::count_if(model.bodies().begin(), model.bodies().end(), on) != 1)
    throw std::runtime_error("frame '" + model.frames()[static_cast<std::size_t>(frame)].name +
                             "': not exactly one body");
  return barFrom(model, *std::find_if(model.bodies().begin(), model.bodies().end(), on));
}

/// The scene's pins in the order of `coordinates` (their names), with its initial state, spherical cuts,
/// undamped point springs, constant joint actuations and gravity; anything else throws, so that the
/// Simbody model built from it is the scene's mechanism, all of it.
peer::PinTree pinTreeOf(const mbsopt::Scene& scene, const std::vector<std::string>& coordinates) {
  const mbsopt::Model& m = scene.model;
  if (static_cast<int>(coordinates.size()) != m.coordinateCount() || !m.drivenCoordinates().empty())
    throw std::runtime_error("pinTreeOf: every coordinate, none driven, must be listed");
  std::vector<int> position(coordinates.size());  // a model coordinate's position in `coordinates`
  for (std::size_t i = 0; i < coordinates.size(); ++i)
    position[static_cast<std::size_t>(m.coordinate(coordinates[i]))] = static_cast<int>(i);
  const auto at = [&](mbsopt::FrameIndex frame, const Eigen::Vector3d& point) {
    peer::PinPoint p = pinPoint(m, frame, point);
    if (p.pin >= 0) p.pin = position[static_cast<std::size_t>(p.pin)];
    return p;
  };
  const Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  peer::PinTree tree;
  for (const std::string& name : coordinates) {
    const int c = m.coordinate(name);
    const int element = m.coordinates()[static_cast<std::size_t>(c)].element;
    const mbsopt::KinematicElement& joint = m.elements()[static_cast<std::size_t>(element)];
    const auto* revolute = std::get_if<mbsopt::RevoluteJoint>(&joint.kind);
    if (!revolute || revolute->axis != Eigen::Vector3d::UnitZ())
      throw std::runtime_error("joint '" + name + "': only revolute joints about z here");
    const peer::PinPoint location = at(joint.entry, origin);
    tree.pins.push_back({location.pin, location.point, barOn(m, joint.exit), scene.q0[c], scene.v0[c]});
  }
  if (m.bodies().size() != coordinates.size()) throw std::runtime_error("pinTreeOf: a body not on a joint's frame");
  for (const mbsopt::CutJoint& cut : m.cuts()) {
    // Between pins about z, a revolute cut about z holds its two origins together and nothing else.
    const auto* spherical = std::get_if<mbsopt::SphericalCut>(&cut.kind);
    const auto* revolute = std::get_if<mbsopt::RevoluteCut>(&cut.kind);
    if (revolute && revolute->axis_in_a == Eigen::Vector3d::UnitZ() && revolute->axis_in_b == Eigen::Vector3d::UnitZ())
      tree.closures.push_back({at(revolute->frame_a, origin), at(revolute->frame_b, origin)});
    else if (spherical)
      tree.closures.push_back({at(spherical->frame_a, origin), at(spherical->frame_b, origin)});
    else
      throw std::runtime_error("cut '" + cut.name + "': only spherical cuts and revolute cuts about z here");
  }
  for (const mbsopt::ForceElement& force : m.forces()) {
    const auto* spring = std::get_if<mbsopt::PointSpringDamper>(&force);
    const auto* actuation = std::get_if<mbsopt::JointActuation>(&force);
    if (spring && m.value(spring->damping) == 0.0) {
      tree.springs.push_back({at(spring->frame_a, spring->point_a), at(spring->frame_b, spring->point_b),
                              m.value(spring->stiffness), m.value(spring->rest_length)});
    } else if (actuation && actuation->force.isConstant()) {
      tree.torques.push_back({position[static_cast<std::size_t>(actuation->coordinate)], m.value(actuation->force, 0.0)});
    } else {
      throw std::runtime_error("pinTreeOf: only undamped point springs and constant joint actuations here");
    }
  }
  tree.gravity = array3(m.gravity());
  return tree;
}

/// `links` uniform links (length L, mass m, I = mL²/12 about the centre) pinned about z, horizontal
/// along x at rest, gravity −9.81 along y.
mbsopt::Scene chainScene(int links, double length, double mass) {
  mbsopt::Scene scene;
  mbsopt::Model& m = scene.model;
  m.setGravity(Eigen::Vector3d(0.0, -9.81, 0.0));
  const double inertia = mass * length * length / 12.0;
  mbsopt::FrameIndex tip = mbsopt::Model::ground;
  for (int i = 0; i < links; ++i) {
    const mbsopt::FrameIndex link = m.addRevolute("joint" + std::to_string(i), tip, Eigen::Vector3d::UnitZ());
    m.addBody("link" + std::to_string(i), link, mass, Eigen::Vector3d(0.5 * length, 0.0, 0.0),
              inertia * Eigen::Matrix3d::Identity());
    tip = m.addOffset("tip" + std::to_string(i), link, Eigen::Vector3d(length, 0.0, 0.0));
  }
  scene.q0 = Eigen::VectorXd::Zero(m.coordinateCount());
  scene.v0 = Eigen::VectorXd::Zero(m.coordinateCount());
  return scene;
}

/// IFToMM A02 with N windows: rockers `rocker<i>` (i = 0..N) pinned to the ground at (i, 0), couplers
/// `coupler<i>` (i = 0..N−1) pinned on rocker i's tip, each coupler's tip held on rocker i+1's tip by
/// a spherical cut (3 equations, the one along z vanishing in the plane: dropped by the SVD).
mbsopt::Scene nFourBarScene(int n, double rocker_angle, double rocker_rate) {
  mbsopt::Scene scene;
  mbsopt::Model& m = scene.model;
  m.setGravity(Eigen::Vector3d(0.0, -9.81, 0.0));
  const double inertia = 1.0 / 12.0;
  std::vector<mbsopt::FrameIndex> rocker_tips;
  for (int i = 0; i <= n; ++i) {
    const std::string name = "rocker" + std::to_string(i);
    const mbsopt::FrameIndex pivot =
        m.addOffset(name + "_pivot", mbsopt::Model::ground, Eigen::Vector3d(double(i), 0.0, 0.0));
    const mbsopt::FrameIndex rocker = m.addRevolute(name, pivot, Eigen::Vector3d::UnitZ());
    m.addBody(name + "_bar", rocker, 1.0, Eigen::Vector3d(0.5, 0.0, 0.0), inertia * Eigen::Matrix3d::Identity());
    rocker_tips.push_back(m.addOffset(name + "_tip", rocker, Eigen::Vector3d(1.0, 0.0, 0.0)));
  }
  for (int i = 0; i < n; ++i) {
    const std::string name = "coupler" + std::to_string(i);
    const mbsopt::FrameIndex coupler = m.addRevolute(name, rocker_tips[i], Eigen::Vector3d::UnitZ());
    m.addBody(name + "_bar", coupler, 1.0, Eigen::Vector3d(0.5, 0.0, 0.0), inertia * Eigen::Matrix3d::Identity());
    const mbsopt::FrameIndex tip = m.addOffset(name + "_tip", coupler, Eigen::Vector3d(1.0, 0.0, 0.0));
    m.addSphericalCut(name + "_cut", tip, rocker_tips[i + 1]);
  }
  scene.q0 = Eigen::VectorXd::Zero(m.coordinateCount());
  scene.v0 = Eigen::VectorXd::Zero(m.coordinateCount());
  for (int i = 0; i <= n; ++i) {
    const int c = m.coordinate("rocker" + std::to_string(i));
    scene.q0[c] = rocker_angle;
    scene.v0[c] = rocker_rate;
  }
  for (int i = 0; i < n; ++i) {
    const int c = m.coordinate("coupler" + std::to_string(i));
    scene.q0[c] = -rocker_angle;
    scene.v0[c] = -rocker_rate;
  }
  return scene;
}

/// Rockers 60° from the hanging position (−90° + 60°): the parallelogram swings with an amplitude of
/// 60° and never reaches the horizontal, where A02's own start (vertical, 1 m/s) takes it.
const double kSwingAngle = -std::numbers::pi / 6.0;

std::vector<Mechanism> allMechanisms() {
  std::vector<Mechanism> list;
  {
    Mechanism m;
    m.key = "four_bar";
    m.description = "four-bar of problems/scenes/four_bar.yaml (loaded by the scene loader), released from rest, 4 s";
    m.end_time = 4.0;
    m.coordinates = {"crank", "coupler", "rocker"};
    m.mbsopt_scene = fourBarScene;
    m.simbody_model = [] {
      const mbsopt::Scene scene = fourBarScene();
      return peer::SimbodyModel::fourBar(barOf(scene.model, "crank_bar"), barOf(scene.model, "coupler_bar"),
                                         barOf(scene.model, "rocker_bar"));
    };
    m.ladder = {2, 3, 5, 8, 13, 20, 32, 50, 80, 130, 200, 320, 500, 800, 1300, 2000, 3200};
    m.fine_ladder = {4000, 8000};
    list.push_back(std::move(m));
  }
  {
    Mechanism m;
    m.key = "chain8";
    m.description = "pendulum chain of 8 uniform links (0.5 m, 1 kg, I = mL^2/12), released horizontal from rest, 2 s";
    m.end_time = 2.0;
    for (int i = 0; i < 8; ++i) m.coordinates.push_back("joint" + std::to_string(i));
    m.mbsopt_scene = [] { return chainScene(8, 0.5, 1.0); };
    m.simbody_model = [] { return peer::SimbodyModel::chain(8, 0.5, 1.0); };
    m.ladder = {3, 5, 8, 13, 20, 32, 50, 80, 130, 200, 320, 500, 800, 1300, 2000, 3200, 5000, 8000, 13000};
    m.fine_ladder = {16000, 32000};
    list.push_back(std::move(m));
  }
  for (int n : {4, 16}) {  // A02's geometry, swinging below the horizontal (see kSwingAngle)
    Mechanism m;
    m.key = "nfourbar" + std::to_string(n);
    m.description = "N four-bar of IFToMM A02, N = " + std::to_string(n) + " (" + std::to_string(n + 1) +
                    " rockers, " + std::to_string(n) + " couplers, 1 m, 1 kg each), released from rest with the "
                    "rockers 60 deg from hanging (never horizontal, so never singular), 10 s";
    m.end_time = 10.0;
    for (int i = 0; i <= n; ++i) m.coordinates.push_back("rocker" + std::to_string(i));
    for (int i = 0; i < n; ++i) m.coordinates.push_back("coupler" + std::to_string(i));
    m.mbsopt_scene = [n] { return nFourBarScene(n, kSwingAngle, 0.0); };
    m.simbody_model = [n] { return peer::SimbodyModel::nFourBar(n, kSwingAngle, 0.0); };
    // mbsopt's steps cost more here at small h (more Newton iterations and tangent refreshes per step,
    // see the counters in the JSON): the ladder and the agreement steps stop earlier for N = 16.
    m.ladder = n <= 4 ? std::vector<int>{2, 3, 5, 8, 13, 20, 32, 50, 80, 130, 200, 320, 500, 800, 1300, 2000}
                      : std::vector<int>{2, 3, 5, 8, 13, 20, 32, 50, 80, 130, 200, 320, 500};
    m.fine_ladder = n <= 4 ? std::vector<int>{1000, 2000} : std::vector<int>{500, 1000};
    m.by_default = n <= 4;  // N = 16 takes ~10 minutes on its own (mbsopt ~0.8 ms per step at small h)
    list.push_back(std::move(m));
  }
  {
    Mechanism m;
    m.key = "andrews";
    m.description = "Andrews' squeezing mechanism of problems/scenes/hard/andrews_squeezer.yaml (loaded by the scene "
                    "loader; 7 bodies, 3 loops closed at one point, stiff spring, constant torque, no gravity), "
                    "from rest, 0.03 s";
    m.end_time = 0.03;
    m.output_interval = 0.001;
    m.coordinates = {"crank", "rod", "lever_3", "link_4", "link_5", "link_6", "link_7"};  // the test set's y(1..7)
    m.mbsopt_scene = andrewsScene;
    m.simbody_model = [coordinates = m.coordinates] {
      return peer::SimbodyModel::pinTree(pinTreeOf(andrewsScene(), coordinates));
    };
    // The crank reaches ~1000 rad/s in 0.03 s: the error is ~1 rad at h = 1 ms (the scene's own step is
    // 2e-5 s) and ~2e-8 at 2e-7 s; the agreement steps give ~1e-8 and ~2e-9, ~2e-11 extrapolated.
    m.ladder = {1, 2, 3, 5, 8, 13, 20, 32, 50, 80, 130, 200, 320, 500, 800, 1300, 2000, 3200, 5000};
    m.fine_ladder = {8000, 16000};
    list.push_back(std::move(m));
  }
  {
    Mechanism m;
    m.key = "humanoid";
    m.description = "MuJoCo's sample humanoid.xml read by both engines (a free root, 21 hinges with springs, dampers "
                    "and armature; contacts, limits and actuators off), limbs thrown, 1 s; not in Simbody";
    m.end_time = 1.0;
    m.coordinates = kHumanoidHinges;
    m.mbsopt_scene = [] {
      std::vector<mbsopt::ParameterOverride> throw_;
      for (const auto& [joint, rate] : kHumanoidThrow) throw_.emplace_back(joint + ".v0", rate);
      mbsopt::LoadedScene loaded = mbsopt::loadScene(
          {"humanoid.yaml", "model: {file: " + std::string(kHumanoidFile) + ", ignore: [contacts, limits, actuators]}\n"},
          throw_);
      return std::move(loaded.scene);
    };
    m.mujoco_model = [] {
      return peer::MujocoModel::file(kHumanoidFile, mjDSBL_CONTACT | mjDSBL_LIMIT | mjDSBL_ACTUATION, kHumanoidHinges,
                                     kHumanoidThrow);
    };
    m.ladder = {5, 8, 13, 20, 32, 50, 80, 130, 200, 320, 500, 800, 1300, 2000};
    m.fine_ladder = {2000, 4000};
    list.push_back(std::move(m));
  }
  return list;
}

// ---------------------------------------------------------------------------------------------
// Runs

struct Run {
  std::string engine;      ///< "simbody" | "mbsopt"
  std::string integrator;  ///< Simbody's integrator, or "Newmark"
  double accuracy = kNaN;  ///< Simbody
  double step = kNaN;      ///< mbsopt
  bool ok = false;
  std::string message;
  Outputs outputs;
  std::vector<double> seconds;  ///< every repetition
  double median_seconds = kNaN;
  double error = kNaN;
  json counters = json::object();
};

struct MbsoptRun {
  bool ok = false;
  std::string message;
  Outputs outputs;
  double seconds = 0.0;
  json counters = json::object();
};

MbsoptRun runMbsopt(const mbsopt::Scene& scene, const std::vector<int>& indices, int steps_per_output,
                    double output_interval, int outputs, bool fast_steps = false) {
  MbsoptRun result;
  mbsopt::NewmarkSettings settings = fast_steps ? mbsopt::withFastSteps(scene.settings) : scene.settings;
  settings.step = output_interval / steps_per_output;
  settings.end_time = output_interval * outputs;
  result.outputs.reserve(static_cast<std::size_t>(outputs));
  const auto start = std::chrono::steady_clock::now();
  try {
    mbsopt::NewmarkIntegrator integrator(scene.model, settings);
    integrator.initialize(scene.q0, scene.v0);
    for (int k = 0; k < outputs; ++k) {
      for (int s = 0; s < steps_per_output; ++s) integrator.step();
      std::vector<double> q;
      q.reserve(indices.size());
      for (int i : indices) q.push_back(integrator.q()[i]);
      result.outputs.push_back(std::move(q));
    }
    result.ok = true;
    const mbsopt::IntegratorStatistics& stats = integrator.statistics();
    result.counters = {{"steps", stats.steps},
                       {"newton_iterations", stats.newton_iterations},
                       {"jacobian_updates", stats.jacobian_updates},
                       {"mass_updates", stats.mass_updates},
                       {"max_closure_error", stats.max_closure_error}};
  } catch (const mbsopt::SimulationError& error) {
    result.message = error.what();
    result.counters = {{"failed_at_time", error.time}, {"failed_at_step", error.step},
                       {"residual_norm", error.residual_norm}};
  } catch (const std::exception& error) {
    result.message = error.what();
  }
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!result.ok) result.outputs.clear();
  return result;
}

/// A run driven by accuracy (`mbsopt simulate --integrator NAME --accuracy TOL`: the extrapolation
/// chooses its macro step and runs, the adaptive Newmark its local tolerance), its results at the output times; the counters add the largest estimated error of
/// the compared coordinates there, and the controller's attempts. The time includes every attempt.
MbsoptRun runMbsoptToAccuracy(const mbsopt::Scene& scene, const std::vector<int>& indices, const std::string& integrator,
                              double tolerance, double output_interval, int outputs) {
  MbsoptRun result;
  mbsopt::NewmarkSettings settings = scene.settings;
  settings.end_time = output_interval * outputs;
  mbsopt::IntegrationRequest request;
  request.integrator.name = integrator;
  request.accuracy = mbsopt::ErrorTolerance{tolerance, 0.0};
  request.output_step = output_interval;
  const auto start = std::chrono::steady_clock::now();
  try {
    const mbsopt::Integration integration = mbsopt::integrate(scene.model, settings, scene.q0, scene.v0, request);
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const mbsopt::Trajectory& t = integration.run.trajectory;
    double estimate = 0.0;
    for (int k = 1; k <= outputs; ++k) {
      std::vector<double> q;
      for (int i : indices) {
        q.push_back(t.q(i, k));
        estimate = std::max(estimate, std::abs(integration.run.q_error(i, k)));
      }
      result.outputs.push_back(std::move(q));
    }
    const mbsopt::IntegratorStatistics& stats = t.statistics;
    result.ok = true;
    result.counters = {{"steps", stats.steps},
                       {"newton_iterations", stats.newton_iterations},
                       {"macro_step", integration.control->macro_step},
                       {"runs", integration.run.steps.size()},
                       {"order", integration.run.order},
                       {"attempts_rejected", integration.control->rejected.size()},
                       {"estimated_error", estimate}};
  } catch (const std::exception& error) {
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    result.message = error.what();
  }
  return result;
}

double maxAbsError(const Outputs& run, const Outputs& reference) {
  if (run.size() != reference.size()) return kNaN;
  double error = 0.0;
  for (std::size_t k = 0; k < run.size(); ++k)
    for (std::size_t i = 0; i < run[k].size(); ++i) {
      const double e = std::abs(run[k][i] - reference[k][i]);
      if (!std::isfinite(e)) return std::numeric_limits<double>::infinity();
      error = std::max(error, e);
    }
  return error;
}

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

/// Repetitions after a first run of `first` seconds: 5 below 0.3 s, 3 below 3 s, else 1 (quick: 1).
int repetitionsFor(double first, bool quick) {
  if (quick) return 1;
  if (first < 0.3) return 5;
  if (first < 3.0) return 3;
  return 1;
}

// ---------------------------------------------------------------------------------------------
// Fronts and ratios

struct Point {
  double error, seconds;
  std::string label;
};

/// Runs not dominated by a faster one: sorted by time, each strictly more accurate than all faster.
std::vector<Point> paretoFront(std::vector<Point> points) {
  std::erase_if(points, [](const Point& p) { return !(std::isfinite(p.error) && p.error > 0.0); });
  std::sort(points.begin(), points.end(), [](const Point& a, const Point& b) { return a.seconds < b.seconds; });
  std::vector<Point> front;
  for (const Point& p : points)
    if (front.empty() || p.error < front.back().error) front.push_back(p);
  return front;
}

/// An engine's time at an error: interpolated between two runs, or an upper bound.
struct TimeAtError {
  double seconds;
  bool upper_bound;  ///< its cheapest run is already more accurate: the time is that run's, at most
};

/// Time to reach `error` on a front, log-log between the two front points that bracket it; the
/// cheapest run's time, as an upper bound, when that run already reaches it (a cheaper setting, not
/// run, might too); nullopt when no run reaches it.
std::optional<TimeAtError> timeAtError(const std::vector<Point>& front, double error) {
  if (front.empty()) return std::nullopt;
  if (front[0].error <= error) return TimeAtError{front[0].seconds, front[0].error < error};
  for (std::size_t k = 0; k + 1 < front.size(); ++k) {
    const Point& a = front[k];
    const Point& b = front[k + 1];
    if (a.error >= error && error >= b.error) {
      const double s = (std::log(error) - std::log(a.error)) / (std::log(b.error) - std::log(a.error));
      return TimeAtError{std::exp(std::log(a.seconds) + s * (std::log(b.seconds) - std::log(a.seconds))), false};
    }
  }
  return std::nullopt;
}

/// A time in ms, "≤ t" for an upper bound, "—" for none.
std::string formatTime(const std::optional<TimeAtError>& time);

/// peer / mbsopt from their times at one error, with its sign of bound: "≥ r" when mbsopt's time is
/// an upper bound, "≤ r" when the peer's is, "—" when both are or either is missing.
std::string formatRatio(const std::optional<TimeAtError>& peer, const std::optional<TimeAtError>& mbsopt);

json frontJson(const std::vector<Point>& front) {
  json out = json::array();
  for (const Point& p : front) out.push_back({{"error", p.error}, {"seconds", p.seconds}, {"run", p.label}});
  return out;
}

std::string format(double value, int precision = 3) {
  if (!std::isfinite(value)) return "—";
  std::ostringstream out;
  out << std::setprecision(precision) << value;
  return out.str();
}

std::string formatTime(const std::optional<TimeAtError>& time) {
  if (!time) return "—";
  return (time->upper_bound ? "≤ " : "") + format(time->seconds * 1e3, 3);
}

std::string formatRatio(const std::optional<TimeAtError>& peer, const std::optional<TimeAtError>& mbsopt) {
  if (!peer || !mbsopt || (peer->upper_bound && mbsopt->upper_bound)) return "—";
  const std::string bound = mbsopt->upper_bound ? "≥ " : peer->upper_bound ? "≤ " : "";
  return bound + format(peer->seconds / mbsopt->seconds, 3);
}

std::string sci(double value) {
  if (!std::isfinite(value)) return "—";
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.1e", value);
  return buffer;
}

/// A message on one Markdown table line: newlines and '|' replaced, runs of spaces squeezed.
std::string oneLine(const std::string& text) {
  std::string out;
  for (char c : text) {
    const char d = (c == '\n' || c == '\r' || c == '\t') ? ' ' : (c == '|' ? '/' : c);
    if (d == ' ' && (out.empty() || out.back() == ' ')) continue;
    out += d;
  }
  while (!out.empty() && out.back() == ' ') out.pop_back();
  return out;
}

json jsonNumber(double value) { return std::isfinite(value) ? json(value) : json(nullptr); }

// ---------------------------------------------------------------------------------------------

struct Options {
  std::filesystem::path out = "results/peer-comparison";
  bool quick = false;
  std::vector<std::string> mechanisms;
};

Options parse(int argc, char** argv) {
  Options options;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--out" && i + 1 < argc) {
      options.out = argv[++i];
    } else if (arg == "--quick") {
      options.quick = true;
    } else if (arg == "--mechanisms" && i + 1 < argc) {
      std::stringstream list(argv[++i]);
      for (std::string name; std::getline(list, name, ',');) options.mechanisms.push_back(name);
    } else {
      std::cerr << "usage: peer_comparison [--out DIR] [--quick] "
                   "[--mechanisms four_bar,chain8,nfourbar4,andrews,humanoid,nfourbar16,a02_singular]\n";
      std::exit(arg == "--help" || arg == "-h" ? 0 : 2);
    }
  }
  return options;
}

struct MechanismResult {
  json data;
  std::vector<std::string> table_rows;
  std::vector<std::string> agreement_rows;
  std::vector<std::string> failure_rows;
};

MechanismResult compare(const Mechanism& mech, const Options& options, const std::filesystem::path& out) {
  const int outputs = static_cast<int>(std::lround(mech.end_time / mech.output_interval));
  std::vector<double> output_times;
  for (int k = 1; k <= outputs; ++k) output_times.push_back(k * mech.output_interval);

  const mbsopt::Scene scene = mech.mbsopt_scene();
  std::vector<int> indices;
  for (const std::string& name : mech.coordinates) indices.push_back(scene.model.coordinate(name));
  const std::unique_ptr<peer::SimbodyModel> simbody = mech.simbody_model ? mech.simbody_model() : nullptr;
  if (simbody && simbody->coordinateCount() != static_cast<int>(indices.size()))
    throw std::runtime_error(mech.key + ": the two models have different coordinate counts");
  // MuJoCo: a model file's own, or the same pins written as MJCF.
  std::string mujoco_absent;
  std::unique_ptr<peer::MujocoModel> mujoco;
  try {
    mujoco = mech.mujoco_model ? mech.mujoco_model()
                               : peer::MujocoModel::pinTree(pinTreeOf(scene, mech.coordinates), mujoco_absent);
  } catch (const std::exception& error) {
    mujoco_absent = error.what();
  }

  std::cerr << "== " << mech.key << ": " << mech.description << '\n';
  MechanismResult result;
  json& data = result.data;
  data["name"] = mech.key;
  data["description"] = mech.description;
  data["end_time"] = mech.end_time;
  data["output_interval"] = mech.output_interval;
  data["output_times"] = outputs;
  data["coordinates"] = mech.coordinates;

  // Reference and agreement: the first Simbody integrator that gets through at 1e-12 (RungeKuttaMerson,
  // then RungeKuttaFeldberg, then CPodes), the others checked against it; without a Simbody model,
  // MuJoCo's RK4 at the finest agreement step, checked against RK4 at the other.
  Outputs reference_outputs;
  std::string reference_name;
  json agreement = json::object();
  if (simbody) {
    const std::vector<peer::SimbodyIntegrator> tight = {peer::SimbodyIntegrator::RungeKuttaMerson,
                                                        peer::SimbodyIntegrator::RungeKuttaFeldberg,
                                                        peer::SimbodyIntegrator::CPodes};
    std::vector<peer::SimbodyRun> tight_runs;
    int reference_index = -1;
    for (std::size_t i = 0; i < tight.size(); ++i) {
      tight_runs.push_back(simbody->run(tight[i], 1e-12, output_times, kReferenceBudget));
      std::cerr << "   simbody " << peer::integratorName(tight[i]) << " at 1e-12: "
                << (tight_runs.back().ok ? "ok" : "FAILED " + oneLine(tight_runs.back().message)) << ", "
                << tight_runs.back().steps << " steps, " << tight_runs.back().seconds << " s\n";
      if (tight_runs.back().ok && reference_index < 0) reference_index = static_cast<int>(i);
    }
    if (reference_index < 0) throw std::runtime_error(mech.key + ": every Simbody integrator failed at 1e-12");
    const peer::SimbodyRun& reference = tight_runs[static_cast<std::size_t>(reference_index)];
    reference_name = peer::integratorName(tight[static_cast<std::size_t>(reference_index)]);
    reference_outputs = reference.outputs;
    data["reference"] = {{"engine", "simbody"}, {"integrator", reference_name}, {"accuracy", 1e-12},
                         {"seconds", reference.seconds}, {"steps", reference.steps}};
    for (std::size_t i = 0; i < tight.size(); ++i) {
      if (static_cast<int>(i) == reference_index) continue;
      const peer::SimbodyRun& check = tight_runs[i];
      const double e = check.ok ? maxAbsError(check.outputs, reference_outputs) : kNaN;
      agreement[std::string("simbody_") + peer::integratorName(tight[i]) + "_1e-12"] = {
          {"error", jsonNumber(e)}, {"ok", check.ok}, {"message", check.message}, {"seconds", check.seconds}};
      result.agreement_rows.push_back("| " + mech.key + " | " + reference_name + " | Simbody " +
                                      peer::integratorName(tight[i]) + " at 1e-12 | " +
                                      (check.ok ? sci(e) : "failed: " + oneLine(check.message)) + " |");
    }
  } else {
    if (!mujoco) throw std::runtime_error(mech.key + ": neither Simbody nor MuJoCo gives a reference");
    const double coarse_step = mech.output_interval / mech.fine_ladder.front();
    const double fine_step = mech.output_interval / mech.fine_ladder.back();
    const peer::MujocoRun reference = mujoco->run(peer::MujocoIntegrator::RK4, fine_step, output_times);
    const peer::MujocoRun check = mujoco->run(peer::MujocoIntegrator::RK4, coarse_step, output_times);
    if (!reference.ok) throw std::runtime_error(mech.key + ": MuJoCo's RK4 reference failed: " + reference.message);
    reference_name = "MuJoCo RK4, h = " + sci(fine_step);
    reference_outputs = reference.outputs;
    data["reference"] = {{"engine", "mujoco"}, {"integrator", "RK4"}, {"step", fine_step},
                         {"seconds", reference.seconds}, {"steps", reference.steps}};
    const double e = check.ok ? maxAbsError(check.outputs, reference_outputs) : kNaN;
    agreement["mujoco_RK4_h_" + sci(coarse_step)] = {{"error", jsonNumber(e)}, {"ok", check.ok}, {"message", check.message}};
    result.agreement_rows.push_back("| " + mech.key + " | " + reference_name + " | MuJoCo RK4, h = " + sci(coarse_step) +
                                    " | " + (check.ok ? sci(e) : "failed: " + oneLine(check.message)) + " |");
  }
  std::vector<MbsoptRun> fine;
  for (int k : mech.fine_ladder) {
    fine.push_back(runMbsopt(scene, indices, k, mech.output_interval, outputs));
    const double h = mech.output_interval / k;
    const double e = fine.back().ok ? maxAbsError(fine.back().outputs, reference_outputs) : kNaN;
    agreement["mbsopt_h_" + sci(h)] = {{"step", h}, {"error", jsonNumber(e)}, {"ok", fine.back().ok},
                                       {"message", fine.back().message}, {"seconds", fine.back().seconds}};
    result.agreement_rows.push_back("| " + mech.key + " | " + reference_name + " | mbsopt Newmark, h = " + sci(h) + " | " +
                                    (fine.back().ok ? sci(e) : "failed: " + oneLine(fine.back().message)) + " |");
    std::cerr << "   mbsopt h = " << h << ": " << (fine.back().ok ? sci(e) : fine.back().message) << '\n';
  }
  double richardson_error = kNaN;
  if (fine.size() == 2 && fine[0].ok && fine[1].ok) {
    Outputs extrapolated = fine[1].outputs;  // (4 q(h/2) − q(h)) / 3
    for (std::size_t k = 0; k < extrapolated.size(); ++k)
      for (std::size_t i = 0; i < extrapolated[k].size(); ++i)
        extrapolated[k][i] = (4.0 * fine[1].outputs[k][i] - fine[0].outputs[k][i]) / 3.0;
    richardson_error = maxAbsError(extrapolated, reference_outputs);
    result.agreement_rows.push_back("| " + mech.key + " | " + reference_name + " | mbsopt, Richardson extrapolation of the two | " +
                                    sci(richardson_error) + " |");
  }
  agreement["mbsopt_richardson"] = jsonNumber(richardson_error);
  double best_mbsopt = richardson_error;
  for (const MbsoptRun& run : fine)
    if (run.ok) best_mbsopt = std::min(std::isfinite(best_mbsopt) ? best_mbsopt : 1e300, maxAbsError(run.outputs, reference_outputs));
  agreement["threshold"] = kAgreementThreshold;
  agreement["mbsopt_best"] = jsonNumber(best_mbsopt);
  agreement["both_engines_agree"] = std::isfinite(best_mbsopt) && best_mbsopt <= kAgreementThreshold;
  data["agreement"] = agreement;
  std::cerr << "   agreement: Richardson " << sci(richardson_error) << '\n';

  // Sweeps.
  std::vector<Run> runs;
  const std::vector<double> accuracies = options.quick ? std::vector<double>{1e-2, 1e-4, 1e-6, 1e-8}
                                                       : std::vector<double>{1e-2, 1e-3, 1e-4, 1e-5, 1e-6,
                                                                             1e-7, 1e-8, 1e-9, 1e-10};
  for (peer::SimbodyIntegrator kind : {peer::SimbodyIntegrator::RungeKuttaFeldberg,
                                       peer::SimbodyIntegrator::RungeKuttaMerson, peer::SimbodyIntegrator::CPodes}) {
    if (!simbody) break;
    for (double accuracy : accuracies) {
      Run run;
      run.engine = "simbody";
      run.integrator = peer::integratorName(kind);
      run.accuracy = accuracy;
      peer::SimbodyRun first = simbody->run(kind, accuracy, output_times, kRunBudget);
      run.seconds.push_back(first.seconds);
      const int repetitions = repetitionsFor(first.seconds, options.quick);
      for (int r = 1; r < repetitions; ++r) run.seconds.push_back(simbody->run(kind, accuracy, output_times, kRunBudget).seconds);
      run.ok = first.ok;
      run.message = first.message;
      run.outputs = std::move(first.outputs);
      run.median_seconds = median(run.seconds);
      run.counters = {{"steps", first.steps}, {"step_attempts", first.step_attempts},
                      {"realizations", first.realizations}, {"projections", first.projections}};
      run.error = run.ok ? maxAbsError(run.outputs, reference_outputs) : kNaN;
      std::cerr << "   simbody " << std::setw(18) << run.integrator << " acc " << sci(accuracy) << ": error "
                << sci(run.error) << ", " << format(run.median_seconds) << " s" << (run.ok ? "" : " FAILED " + oneLine(run.message))
                << '\n';
      runs.push_back(std::move(run));
    }
  }
  std::vector<int> ladder = mech.ladder;
  if (options.quick) {
    std::vector<int> thinned;
    for (std::size_t i = 0; i < ladder.size(); i += 3) thinned.push_back(ladder[i]);
    ladder = thinned;
  }
  // MuJoCo: its three integrators over the same ladder of fixed steps.
  data["mujoco"] = mujoco ? json{{"mjcf", mujoco->mjcf()}} : json{{"absent", mujoco_absent}};
  if (!mujoco) std::cerr << "   mujoco: not run (" << oneLine(mujoco_absent) << ")\n";
  for (peer::MujocoIntegrator kind : {peer::MujocoIntegrator::Euler, peer::MujocoIntegrator::Implicit,
                                      peer::MujocoIntegrator::RK4}) {
    if (!mujoco) break;
    for (int k : ladder) {
      Run run;
      run.engine = "mujoco";
      run.integrator = peer::integratorName(kind);
      run.step = mech.output_interval / k;
      peer::MujocoRun first = mujoco->run(kind, run.step, output_times);
      run.seconds.push_back(first.seconds);
      const int repetitions = repetitionsFor(first.seconds, options.quick);
      for (int r = 1; r < repetitions; ++r) run.seconds.push_back(mujoco->run(kind, run.step, output_times).seconds);
      run.ok = first.ok;
      run.message = first.message;
      run.outputs = std::move(first.outputs);
      run.median_seconds = median(run.seconds);
      run.counters = {{"steps", first.steps}};
      run.error = run.ok ? maxAbsError(run.outputs, reference_outputs) : kNaN;
      std::cerr << "   mujoco  " << std::setw(18) << run.integrator << " h " << sci(run.step) << ": error "
                << sci(run.error) << ", " << format(run.median_seconds) << " s" << (run.ok ? "" : " FAILED " + oneLine(run.message))
                << '\n';
      runs.push_back(std::move(run));
    }
  }
  // One mbsopt run of the sweep: `once()` timed over the repetitions, its first result compared.
  const auto sweep = [&](Run run, const std::function<MbsoptRun()>& once) {
    MbsoptRun first = once();
    run.seconds.push_back(first.seconds);
    const int repetitions = repetitionsFor(first.seconds, options.quick);
    for (int r = 1; r < repetitions; ++r) run.seconds.push_back(once().seconds);
    run.ok = first.ok;
    run.message = first.message;
    run.outputs = std::move(first.outputs);
    run.median_seconds = median(run.seconds);
    run.counters = first.counters;
    run.error = run.ok ? maxAbsError(run.outputs, reference_outputs) : kNaN;
    std::cerr << "   mbsopt  " << run.integrator << " "
              << (std::isfinite(run.step) ? "h " + sci(run.step) : "acc " + sci(run.accuracy)) << ": error "
              << sci(run.error);
    if (run.counters.contains("estimated_error")) std::cerr << " (estimated " << sci(run.counters["estimated_error"].get<double>()) << ")";
    std::cerr << ", " << format(run.median_seconds) << " s" << (run.ok ? "" : " FAILED " + oneLine(run.message)) << '\n';
    runs.push_back(std::move(run));
  };
  // The fixed step twice: every step solved to the Newton tolerance, and each step solved only as
  // precisely as it approximates the motion (`simulate --fast-steps`).
  for (const auto& [integrator, fast] : {std::pair{"Newmark", false}, {"Newmark, fast steps", true}})
    for (int k : ladder) {
      Run run;
      run.engine = "mbsopt";
      run.integrator = integrator;
      run.step = mech.output_interval / k;
      sweep(std::move(run), [&] { return runMbsopt(scene, indices, k, mech.output_interval, outputs, fast); });
    }
  for (const std::string integrator : {"extrapolation", "adaptive"})
    for (double tolerance : accuracies) {
      // The adaptive Newmark is of order 2: below 1e-7 a run takes seconds (four-bar, Andrews) and stays
      // off the front by two orders of magnitude.
      if (mbsopt::integratorInfo(integrator).variable_steps && tolerance < kAdaptiveDownTo) continue;
      Run run;
      run.engine = "mbsopt";
      run.integrator = integrator;
      run.accuracy = tolerance;
      sweep(std::move(run),
            [&] { return runMbsoptToAccuracy(scene, indices, integrator, tolerance, mech.output_interval, outputs); });
    }

  // Fronts.
  std::map<std::string, std::vector<Point>> series;  // "mbsopt Newmark", "simbody CPodes", ...
  json runs_json = json::array();
  for (const Run& run : runs) {
    const std::string label = std::isfinite(run.step) ? "h=" + sci(run.step) : "accuracy=" + sci(run.accuracy);
    if (run.ok) series[run.engine + " " + run.integrator].push_back({run.error, run.median_seconds, label});
    json r = {{"engine", run.engine},
              {"integrator", run.integrator},
              {"status", run.ok ? "ok" : "failed"},
              {"error", jsonNumber(run.error)},
              {"median_seconds", run.median_seconds},
              {"seconds", run.seconds},
              {"counters", run.counters}};
    if (std::isfinite(run.step)) r["step"] = run.step; else r["accuracy"] = run.accuracy;
    if (!run.ok) {
      r["message"] = run.message;
      result.failure_rows.push_back("| " + mech.key + " | " + run.engine + " " + run.integrator + " | " + label + " | " +
                                    oneLine(run.message) + " |");
    }
    runs_json.push_back(std::move(r));
  }
  data["runs"] = runs_json;
  std::map<std::string, std::vector<Point>> engine_points;  // "mbsopt", "simbody", "mujoco"
  json fronts = json::object();
  for (const auto& [name, points] : series) {
    fronts[name] = frontJson(paretoFront(points));
    auto& all = engine_points[name.substr(0, name.find(' '))];
    for (Point p : points) {
      p.label = name + " " + p.label;
      all.push_back(p);
    }
  }
  data["fronts"] = {{"per_integrator", fronts}};
  for (const auto& [engine, points] : engine_points) data["fronts"][engine] = frontJson(paretoFront(points));

  json ratios = json::array();
  for (double target : kTargetErrors) {
    // Each engine's time: the fastest of its integrators, each interpolated on its own front (on the
    // engines' joint fronts a slower run a hair more accurate than a faster one sits between it and
    // the next, and the interpolation then runs through the slower one).
    const auto fastest = [&](const std::string& engine) {
      std::pair<std::optional<TimeAtError>, std::string> best;  // the time and the integrator's name
      for (const auto& [name, points] : series)
        if (name.starts_with(engine + " "))
          if (const std::optional<TimeAtError> t = timeAtError(paretoFront(points), target);
              t && (!best.first || t->seconds < best.first->seconds))
            best = {t, name.substr(engine.size() + 1)};
      return best;
    };
    const auto [mbsopt_time, mbsopt_winner] = fastest("mbsopt");
    const auto [simbody_time, winner] = fastest("simbody");
    const auto [mujoco_time, mujoco_winner] = fastest("mujoco");
    const auto ratioOf = [&](const std::optional<TimeAtError>& peer) {
      return (mbsopt_time && peer) ? peer->seconds / mbsopt_time->seconds : kNaN;
    };
    const double ratio = ratioOf(simbody_time), mujoco_ratio = ratioOf(mujoco_time);
    std::string verdict = "not bracketed";
    if (std::isfinite(ratio)) {
      // A bound on mbsopt's time bounds the ratio from below, one on Simbody's from above.
      const bool mbsopt_faster = ratio > 1.0 && !simbody_time->upper_bound;
      const bool simbody_faster = ratio < 1.0 && !mbsopt_time->upper_bound;
      verdict = mbsopt_faster ? "mbsopt faster" : simbody_faster ? "Simbody faster" : "undecided (a bound)";
    } else if (mbsopt_time && !simbody_time) verdict = "Simbody does not reach it";
    else if (!mbsopt_time && simbody_time) verdict = "mbsopt does not reach it";
    if (!simbody) verdict = "not in Simbody";
    const auto seconds = [](const std::optional<TimeAtError>& t) { return t ? json(t->seconds) : json(nullptr); };
    const auto bound = [](const std::optional<TimeAtError>& t) { return t ? json(t->upper_bound) : json(nullptr); };
    ratios.push_back({{"error", target},
                      {"mbsopt_seconds", seconds(mbsopt_time)},
                      {"mbsopt_seconds_is_upper_bound", bound(mbsopt_time)},
                      {"simbody_seconds", seconds(simbody_time)},
                      {"simbody_seconds_is_upper_bound", bound(simbody_time)},
                      {"simbody_integrator", winner.empty() ? json(nullptr) : json(winner)},
                      {"mbsopt_integrator", mbsopt_winner.empty() ? json(nullptr) : json(mbsopt_winner)},
                      {"ratio_simbody_over_mbsopt", jsonNumber(ratio)},
                      {"verdict", verdict},
                      {"mujoco_seconds", seconds(mujoco_time)},
                      {"mujoco_seconds_is_upper_bound", bound(mujoco_time)},
                      {"mujoco_integrator", mujoco_winner.empty() ? json(nullptr) : json(mujoco_winner)},
                      {"ratio_mujoco_over_mbsopt", jsonNumber(mujoco_ratio)}});
    result.table_rows.push_back("| " + mech.key + " | " + sci(target) + " | " + formatTime(mbsopt_time) + " | " +
                                (mbsopt_winner.empty() ? "—" : mbsopt_winner) + " | " + formatTime(simbody_time) + " | " +
                                (winner.empty() ? "—" : winner) + " | " + formatRatio(simbody_time, mbsopt_time) + " | " +
                                verdict + " | " + formatTime(mujoco_time) + " | " +
                                (mujoco_winner.empty() ? (mujoco ? "—" : "not run") : mujoco_winner) + " | " +
                                formatRatio(mujoco_time, mbsopt_time) + " |");
  }
  data["time_ratio"] = ratios;

  // Plot data: one block per series, "error seconds label".
  const std::string base = "work_precision_" + mech.key;
  {
    std::ofstream dat(out / (base + ".dat"));
    dat << "# " << mech.description << "\n# error[rad] median_seconds run\n";
    std::vector<std::string> names;
    for (const auto& [name, points] : series) {
      names.push_back(name);
      std::vector<Point> sorted = points;
      std::sort(sorted.begin(), sorted.end(), [](const Point& a, const Point& b) { return a.seconds < b.seconds; });
      dat << "# " << name << '\n';
      for (const Point& p : sorted) dat << std::setprecision(6) << p.error << ' ' << p.seconds << ' ' << p.label << '\n';
      dat << "\n\n";
    }
    std::ofstream gp(out / (base + ".gp"));
    gp << "set terminal pngcairo noenhanced size 900,600\n"
       << "set output '" << base << ".png'\n"
       << "set title \"" << mech.key << ": work-precision, Simbody " << peer::simbodyVersion()
       << " and MuJoCo " << peer::mujocoVersion() << " vs mbsopt\\nSimbody: " << MBSOPT_PEER_SIMBODY_BUILD << "\"\n"
       << "set logscale xy\nset format x '1e%T'\nset format y '1e%T'\n"
       << "set xlabel 'max abs joint-angle error at the output times [rad]'\n"
       << "set ylabel 'wall time of the integration [s] (median)'\n"
       << "set grid\nset key top right\nset xrange [*:*] reverse\n"
       << "plot ";
    // mbsopt's integrators in reds, Simbody's in greens, MuJoCo's in blues, each with its own marker.
    const std::map<std::string, std::string> styles{
        {"mbsopt Newmark", "lw 3 pt 7 lc rgb '#d62728'"},
        {"mbsopt extrapolation", "lw 3 pt 9 lc rgb '#8c1a1a'"},
        {"mbsopt Newmark, fast steps", "lw 3 pt 11 lc rgb '#e377c2'"},
        {"mbsopt adaptive", "lw 3 pt 5 lc rgb '#ff9896'"},
        {"simbody RungeKuttaFeldberg", "lw 1.5 pt 4 lc rgb '#2ca02c'"},
        {"simbody RungeKuttaMerson", "lw 1.5 pt 6 lc rgb '#98df8a'"},
        {"simbody CPodes", "lw 1.5 pt 8 lc rgb '#17becf'"},
        {"mujoco Euler", "lw 1.5 pt 10 lc rgb '#aec7e8'"},
        {"mujoco implicit", "lw 1.5 pt 12 lc rgb '#6baed6'"},
        {"mujoco RK4", "lw 1.5 pt 14 lc rgb '#1f3f9f'"}};
    for (std::size_t i = 0; i < names.size(); ++i) {
      const auto style = styles.find(names[i]);
      gp << (i ? ", \\\n     " : "") << "'" << base << ".dat' index " << i << " using 1:2 with linespoints "
         << (style != styles.end() ? style->second : "lw 1.5 pt " + std::to_string(4 + 2 * static_cast<int>(i)))
         << " title '" << names[i] << "'";
    }
    gp << '\n';
  }
  return result;
}

/// IFToMM A02 as specified (N = 4, rockers vertical, B0 at 1 m/s along +x, 10 s): the linkage passes
/// the horizontal, singular, configuration twice per turn. No 1e-12 reference exists there (every
/// Simbody integrator fails at tight accuracy), so this only records which runs get through and where
/// they end up: rocker 0's angle at 10 s (its tip B0 = (cos q, sin q)).
json singularSurvey(const Options& options, std::vector<std::string>& rows) {
  const int n = 4;
  const double angle = 0.5 * std::numbers::pi, rate = -1.0, interval = 0.1;
  const int outputs = 100;
  std::vector<double> output_times;
  for (int k = 1; k <= outputs; ++k) output_times.push_back(k * interval);
  const std::unique_ptr<peer::SimbodyModel> simbody = peer::SimbodyModel::nFourBar(n, angle, rate);
  const mbsopt::Scene scene = nFourBarScene(n, angle, rate);
  std::vector<int> indices = {scene.model.coordinate("rocker0")};
  std::cerr << "== a02_singular: IFToMM A02 as specified, N = 4, 10 s (survey, no reference)\n";
  json runs = json::array();
  auto record = [&](const std::string& engine, const std::string& setting, bool ok, const std::string& message,
                    double seconds, double final_angle) {
    runs.push_back({{"engine", engine}, {"setting", setting}, {"status", ok ? "ok" : "failed"},
                    {"message", message}, {"seconds", seconds}, {"rocker0_at_10s", jsonNumber(final_angle)}});
    rows.push_back("| " + engine + " | " + setting + " | " + (ok ? "ok" : "failed") + " | " +
                   (ok ? format(final_angle, 6) : "—") + " | " + format(seconds, 3) + " | " +
                   oneLine(message).substr(0, 160) + " |");
    std::cerr << "   " << engine << " " << setting << ": " << (ok ? "ok, rocker0(10 s) = " + format(final_angle, 6)
                                                              : "FAILED " + oneLine(message).substr(0, 120)) << '\n';
  };
  const std::vector<double> accuracies = options.quick ? std::vector<double>{1e-4, 1e-8}
                                                       : std::vector<double>{1e-2, 1e-4, 1e-6, 1e-8, 1e-10, 1e-12};
  for (peer::SimbodyIntegrator kind : {peer::SimbodyIntegrator::RungeKuttaFeldberg,
                                       peer::SimbodyIntegrator::RungeKuttaMerson, peer::SimbodyIntegrator::CPodes})
    for (double accuracy : accuracies) {
      const peer::SimbodyRun run = simbody->run(kind, accuracy, output_times, 10.0);
      record(std::string("Simbody ") + peer::integratorName(kind), "accuracy " + sci(accuracy), run.ok, run.message,
             run.seconds, run.ok ? run.outputs.back()[0] : kNaN);
    }
  const std::vector<int> ladder = options.quick ? std::vector<int>{32, 1000} : std::vector<int>{10, 32, 100, 320, 1000, 3200};
  for (int k : ladder) {
    const MbsoptRun run = runMbsopt(scene, indices, k, interval, outputs);
    record("mbsopt Newmark", "h " + sci(interval / k), run.ok, run.message, run.seconds,
           run.ok ? run.outputs.back()[0] : kNaN);
  }
  return {{"description", "IFToMM A02 as specified, N = 4: rockers vertical, B0 at 1 m/s along +x, 10 s; passes the "
                          "singular horizontal configuration; no reference, final angle of rocker 0 only"},
          {"runs", runs}};
}

}  // namespace

int main(int argc, char** argv) {
  const Options options = parse(argc, argv);
  std::filesystem::create_directories(options.out);
  std::vector<Mechanism> mechanisms = allMechanisms();
  if (options.mechanisms.empty()) {
    std::erase_if(mechanisms, [](const Mechanism& m) { return !m.by_default; });
  } else {
    std::erase_if(mechanisms, [&](const Mechanism& m) {
      return std::find(options.mechanisms.begin(), options.mechanisms.end(), m.key) == options.mechanisms.end();
    });
  }
  const auto start = std::chrono::steady_clock::now();
  json all = {{"simbody_version", peer::simbodyVersion()},
              {"simbody_build_note", MBSOPT_PEER_SIMBODY_BUILD},
              {"error_measure",
               "largest absolute joint-angle error [rad] over every coordinate and every output time (every 0.1 s; "
               "andrews every 1 ms), "
               "against Simbody at accuracy 1e-12 (RungeKuttaMerson unless it failed)"},
              {"timing", "wall time of the integration only (models built beforehand), median of 5 repetitions "
                         "below 0.3 s, 3 below 3 s, else 1"},
              {"mbsopt_integrator", "Newmark beta=1/4 gamma=1/2, newton_tolerance 1e-10, position-level closure; at fixed "
                                    "steps (also with --fast-steps: Newton to 1e-3 of the step's truncation error, SVDs "
                                    "started from the last step's), and driven by accuracy (extrapolation; adaptive down "
                                    "to 1e-7; absolute tolerance on the angles)"},
              {"quick", options.quick},
              {"mechanisms", json::array()}};
  std::vector<std::string> table, agreement, failures;
  for (const Mechanism& mech : mechanisms) {
    MechanismResult r = compare(mech, options, options.out);
    all["mechanisms"].push_back(std::move(r.data));
    table.insert(table.end(), r.table_rows.begin(), r.table_rows.end());
    agreement.insert(agreement.end(), r.agreement_rows.begin(), r.agreement_rows.end());
    failures.insert(failures.end(), r.failure_rows.begin(), r.failure_rows.end());
  }
  std::vector<std::string> survey_rows;
  const bool run_survey = options.mechanisms.empty() ||
                          std::find(options.mechanisms.begin(), options.mechanisms.end(), "a02_singular") !=
                              options.mechanisms.end();
  if (run_survey) all["a02_singular_survey"] = singularSurvey(options, survey_rows);
  all["total_seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::ofstream(options.out / "peer_comparison.json") << all.dump(2) << '\n';

  std::ofstream md(options.out / "peer_comparison.md");
  md << "# Simbody " << peer::simbodyVersion() << " and MuJoCo " << peer::mujocoVersion()
     << " vs mbsopt: time at equal error\n\n"
     << "Error: " << all["error_measure"].get<std::string>() << ". Times: "
     << all["timing"].get<std::string>() << ". Simbody: **" << MBSOPT_PEER_SIMBODY_BUILD << "**. MuJoCo: Debian's "
     << "libmujoco-dev, the same pins written as MJCF (loops as soft `connect` equalities, as stiff as MuJoCo "
     << "allows at the step), Euler, implicit and RK4 at the ladder's fixed steps.\n\n"
     << "Ratio = the peer's time / mbsopt's time at the same error; each engine's time that of the fastest of its "
     << "integrators at that error, interpolated log-log on that integrator's Pareto front; \"≤ t\" where the "
     << "integrator's cheapest run is already more accurate (its time bounds the time at that error), and the "
     << "ratio then a bound too. Above 1: mbsopt is faster. The verdict is Simbody's.\n\n"
     << "| mechanism | error [rad] | mbsopt [ms] | mbsopt integrator | Simbody [ms] | Simbody integrator | ratio | "
     << "verdict | MuJoCo [ms] | MuJoCo integrator | MuJoCo ratio |\n"
     << "|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const std::string& row : table) md << row << '\n';
  md << "\n## Agreement with the reference (Simbody at 1e-12; MuJoCo's RK4 where Simbody has no model)\n\n"
     << "| mechanism | reference | run | max abs angle difference [rad] |\n|---|---|---|---|\n";
  for (const std::string& row : agreement) md << row << '\n';
  md << "\n## Failed runs\n\n";
  if (failures.empty()) {
    md << "None.\n";
  } else {
    md << "| mechanism | engine | run | message |\n|---|---|---|---|\n";
    for (const std::string& row : failures) md << row << '\n';
  }
  if (run_survey) {
    md << "\n## IFToMM A02 as specified (N = 4, through the singular configuration): which runs get through\n\n"
       << "No reference: rocker 0's angle at 10 s [rad] only (the runs that agree took the same branch).\n\n"
       << "| engine | setting | status | rocker0 at 10 s | time [s] | message |\n|---|---|---|---|---|---|\n";
    for (const std::string& row : survey_rows) md << row << '\n';
  }
  std::cerr << "wrote " << (options.out / "peer_comparison.json").string() << " and peer_comparison.md in "
            << format(all["total_seconds"].get<double>()) << " s\n";
  return 0;
}
