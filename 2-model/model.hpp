// The immutable description of a mechanism (the "model" of the model/workspace split, docs/design.md §2):
// frames linked by kinetostatic elements in chains from the ground (paper §4.1), bodies, force
// elements with named parameters, drivers, cut joints closing loops (§4.4) and sensors.
#pragma once

#include <Eigen/Core>
#include <array>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "mbsopt/model/time_function.hpp"
#include "mbsopt/model/track.hpp"

namespace mbsopt {

using FrameIndex = int;
/// A model parameter: its position in the model's parameter vector (Model::parameterNames() names
/// them in the same order). Elements hold these indices, never the values, so a value is read
/// through the model (Model::value) or, in code templated on the scalar, through parameter(model,
/// ws, index) (workspace.hpp), which seeds it when a derivative with respect to it is asked for.
enum class ParameterIndex : int {};

// ---- kinetostatic elements: each maps an entry frame to an exit frame (20)-(23) ----
/// Three parameters that form a vector (a centre of mass, the moments of an inertia tensor, a translation).
using ParameterVector3 = std::array<ParameterIndex, 3>;

/// An offset's rotation written as an angle about a fixed unit axis of the entry frame: the angle is
/// a geometric parameter ("NAME.rotation.angle").
struct OffsetTurn {
  Eigen::Vector3d axis;
  ParameterIndex angle;
};
/// Passive: a rotation and a translation, both in the entry frame. The translation is a geometric
/// parameter ("NAME.translation.x", …): a design variable may move it, with exact gradients; so is
/// the angle of a rotation written as an axis and an angle (`turn`).
struct Offset {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  ///< R(axis, angle) of `turn` when it has one
  ParameterVector3 translation;  ///< Model::vector gives its value
  bool rotates = false;  ///< rotation ≠ I or a turn: the kinematics multiply by it (most offsets only translate)
  std::optional<OffsetTurn> turn;  ///< empty for a constant rotation matrix
};
struct RevoluteJoint {  ///< active: rotation q about a unit axis of the entry frame
  Eigen::Vector3d axis;
};
struct PrismaticJoint {  ///< active: translation q along a unit axis of the entry frame
  Eigen::Vector3d axis;
};
/// How the exit frame of a curve slider is oriented.
enum class SliderOrientation {
  FollowTrack,  ///< axes = tangent, normal, binormal of the track (ω_s/e = κ ṡ about the binormal)
  Translate     ///< axes parallel to the entry frame's: the slider only translates
};
enum class TrackIndex : int {};
struct CurveSliderJoint {  ///< active: the exit frame rides a track of the entry frame at arc length q
  TrackIndex track;  ///< Model::track gives its geometry
  SliderOrientation orientation = SliderOrientation::FollowTrack;
};
/// Active: one of the three coordinates of a ball joint, its rotation vector φ = (φ_x, φ_y, φ_z) in
/// the entry frame's axes. The exit frame is the entry frame turned by R(φ) = exp([φ]×) about their
/// common origin, a chart singular only where |φ| reaches 2π (3-algorithms/ball_chart.hpp), never
/// at a quarter turn as Cardan angles are. A ball joint is three such elements in a chain, x, y then
/// z (Model::addBallJoint), through coincident frames: the z element's exit is the ball's exit frame,
/// and the two frames between are not frames of the mechanism, so nothing attaches to them.
struct BallJointComponent {
  int component;  ///< 0, 1, 2 for φ_x, φ_y, φ_z: the ball's x element is `component` elements back
};
using ElementKind = std::variant<Offset, RevoluteJoint, PrismaticJoint, CurveSliderJoint, BallJointComponent>;

struct KinematicElement {
  std::string name;
  FrameIndex entry;
  FrameIndex exit;
  int coordinate;  ///< index into q, or -1 for a passive element
  ElementKind kind;
  /// The nearest active element between this one and the ground, not itself; -1 when there is none.
  int parent_joint;
};

/// Model::centreOfMass and Model::inertia assemble the vector and the tensor.
struct Body {
  std::string name;
  FrameIndex frame;
  ParameterIndex mass;
  ParameterVector3 centre_of_mass;    ///< in the frame's axes, from its origin
  ParameterVector3 moments_of_inertia;  ///< I_xx, I_yy, I_zz about the centre of mass, in the frame's axes
  Eigen::Vector3d products_of_inertia;  ///< I_xy, I_xz, I_yz (constants, not parameters)
};

/// A function of time, f(t) = Σ_k c_k t^k + Σ_j A_j sin(ω_j t + φ_j) (a spring's rest value or
/// moving target, an actuation, a driven joint's motion), whose numbers are model parameters under
/// the scene file's dotted names: a number is one parameter under the input's own name
/// (`spring.rest`, `motor.value`), a function (even of one term) has NAME.polynomial.K and
/// NAME.harmonics.J.amplitude, .angular_frequency, .phase. Model::value(input, t, order) and the
/// residual (through parameter(), so AD differentiates them) evaluate it.
struct TimeInput {
  std::vector<ParameterIndex> coefficients;                ///< c_0, c_1, …
  std::vector<std::array<ParameterIndex, 3>> harmonics;  ///< A_j, ω_j, φ_j
  bool isConstant() const { return coefficients.size() <= 1 && harmonics.empty(); }
};

// ---- force elements ----
/// Q = −k (q − r(t)) − c (q̇ − ṙ(t)): a joint spring-damper (constant rest value r) or a guidance
/// spring pulling the joint towards a moving target r(t).
struct JointSpringDamper {
  std::string name;
  int coordinate;
  ParameterIndex stiffness;
  ParameterIndex damping;
  TimeInput rest;
};
/// Spring-damper along the line between a point of frame a and a point of frame b.
struct PointSpringDamper {
  std::string name;
  FrameIndex frame_a;
  Eigen::Vector3d point_a;
  FrameIndex frame_b;
  Eigen::Vector3d point_b;
  ParameterIndex stiffness;
  ParameterIndex damping;
  ParameterIndex rest_length;
};
/// Generalised force (torque or force) on a joint coordinate, given as a function of time.
struct JointActuation {
  std::string name;
  int coordinate;
  TimeInput force;
};
/// Guidance of a frame by a track: a torsional spring-damper about the track's binormal between the
/// frame's heading and the track heading ψ(s) at a curve slider's arc length s (a bogie held by its
/// wheels): τ = −k Δ − c Δ̇, Δ = heading(frame) − ψ(s), Δ̇ = ω_z − κ(s) ṡ. The generalised force on s
/// is −κ τ (virtual work of the same potential and dissipation). The frame's heading is its x axis,
/// taken in the plane of the track (a bogie frame whose x axis points forward).
struct TrackGuidance {
  std::string name;
  FrameIndex frame;
  int slider_coordinate;  ///< coordinate of a CurveSliderJoint; its entry frame carries the track
  ParameterIndex stiffness;
  ParameterIndex damping;
};
/// A rotational damper between two frames: the torque −c (ω_b − ω_a) on frame b and its opposite on
/// frame a. Across a ball joint (MuJoCo's damping of a ball or of a free joint's rotation) it is the
/// generalised force −c JᵀJ φ̇ on the rotation vector's rates (3-algorithms/ball_chart.hpp).
struct RotationalDamper {
  std::string name;
  FrameIndex frame_a, frame_b;
  ParameterIndex damping;  ///< c [N·m·s/rad], "NAME.c"
};
using ForceElement = std::variant<JointSpringDamper, PointSpringDamper, JointActuation, TrackGuidance, RotationalDamper>;

/// Rotor inertia of a joint (MuJoCo's armature): J q̈ on its own coordinate, a term J on the mass
/// matrix's diagonal with no coupling to the other coordinates (a motor's rotor geared to the
/// joint, its own motion with the frames neglected). J [kg m² on a revolute, kg on a prismatic] is
/// the parameter "JOINT.armature".
struct JointArmature {
  int coordinate;
  ParameterIndex inertia;
};

// ---- cut joints closing loops (34): b(q, t) = 0 ----
struct SphericalCut {  ///< 3 equations: origins of a and b coincide
  FrameIndex frame_a, frame_b;
};
struct RevoluteCut {  ///< 5 equations: origins coincide, axis of a stays normal to two directions ⟂ axis of b
  FrameIndex frame_a, frame_b;
  Eigen::Vector3d axis_in_a, axis_in_b;
};
struct WeldCut {  ///< 6 equations: frames a and b coincide
  FrameIndex frame_a, frame_b;
};
using CutKind = std::variant<SphericalCut, RevoluteCut, WeldCut>;
struct CutJoint {
  std::string name;
  CutKind kind;
};
/// The two frames a cut joint joins: frame_a, frame_b.
inline std::array<FrameIndex, 2> cutFrames(const CutKind& cut) {
  return std::visit([](const auto& c) { return std::array{c.frame_a, c.frame_b}; }, cut);
}

// ---- sensors (outputs) ----
enum class Derivative { Position, Velocity, Acceleration };
/// Component `component` (0 = x, 1 = y, 2 = z) of the position (relative to the origin of `axes`),
/// absolute velocity or absolute acceleration of a point fixed in `frame`, in the axes of `axes`.
struct PointSensor {
  FrameIndex frame;
  Eigen::Vector3d point;
  Derivative quantity;
  FrameIndex axes;
  int component;
};
struct JointSensor {  ///< a joint coordinate, its rate or its acceleration
  int coordinate;
  Derivative quantity;
};
/// Angle of frame b relative to frame a about a unit axis of a (the twist of R_aᵀR_b about it).
struct RelativeAngleSensor {
  FrameIndex frame_a, frame_b;
  Eigen::Vector3d axis;
};
/// Which part of the mechanical energy an EnergySensor reports (3-algorithms/energy.hpp).
enum class EnergyPart { Kinetic, Potential, Total };
/// Mechanical energy of the whole model [J]: kinetic, potential (gravity and springs) or their sum.
struct EnergySensor {
  EnergyPart part;
};
enum class ReactionQuantity { Force, Torque };
/// Component `component` (0 = x, 1 = y, 2 = z) of the force (or of the torque about the common
/// origin) that cut joint `cut` transmits to its frame b from frame a's side, in the axes of frame a,
/// from the multipliers λ (cutReaction in 3-algorithms/closure.hpp).
struct CutReactionSensor {
  int cut;
  ReactionQuantity quantity;
  int component;
};
using SensorKind = std::variant<PointSensor, JointSensor, RelativeAngleSensor, EnergySensor, CutReactionSensor>;
struct Sensor {
  std::string name;
  SensorKind kind;
};

/// A track the curve sliders ride. Its numbers (TrackNumbers) are model parameters under the scene
/// file's dotted names, NAME.origin.x|y|z, NAME.heading and NAME.segments.K.length | radius | angle |
/// end_curvature: a design variable may change its geometry, which the kinematics then differentiate
/// (trackAt in 3-algorithms/track_state.hpp).
struct ModelTrack {
  std::string name;
  Track geometry;  ///< built from the parameters' values; rebuilt by Model::setParameter
  ParameterVector3 origin;
  ParameterIndex heading;
  /// Per segment, its numberCount(type) numbers' indices; a straight's second entry is unused.
  std::vector<std::array<ParameterIndex, 2>> segments;
};

struct Frame {
  std::string name;
  int element;  ///< the element whose exit this frame is; -1 for the ground
  int depth;    ///< the number of elements on the path from the ground (0 for the ground)
};

struct Coordinate {
  std::string name;
  int element;       ///< the active element that owns it
  bool driven;       ///< prescribed as a function of time, removed from the unknowns
  TimeInput motion;  ///< when driven: its numbers are model parameters (JOINT.motion…)
};

class Model {
 public:
  static constexpr FrameIndex ground = 0;

  Model();

  // Chains: each call adds an element after frame `parent` and returns its exit frame.
  FrameIndex addOffset(const std::string& name, FrameIndex parent, const Eigen::Vector3d& translation,
                       const Eigen::Matrix3d& rotation = Eigen::Matrix3d::Identity());
  /// An offset turned by `angle` about `axis` (normalised) of the entry frame, the angle a parameter
  /// (NAME.rotation.angle, see OffsetTurn).
  FrameIndex addOffset(const std::string& name, FrameIndex parent, const Eigen::Vector3d& translation,
                       const Eigen::Vector3d& axis, double angle);
  FrameIndex addRevolute(const std::string& name, FrameIndex parent, const Eigen::Vector3d& axis);
  FrameIndex addPrismatic(const std::string& name, FrameIndex parent, const Eigen::Vector3d& axis);
  /// A ball joint (BallJointComponent) about the origin of `parent`: three elements and their
  /// coordinates named `names` [rad], the rotation vector's x, y and z in `parent`'s axes; returns
  /// the exit frame, named names[2].
  FrameIndex addBallJoint(const std::array<std::string, 3>& names, FrameIndex parent);
  /// A track for curve sliders; its numbers become parameters (see ModelTrack).
  TrackIndex addTrack(const std::string& name, const Track& track);
  FrameIndex addCurveSlider(const std::string& name, FrameIndex parent, TrackIndex track,
                            SliderOrientation orientation = SliderOrientation::FollowTrack);
  /// A body attached to `frame` (it adds inertia to that frame; it does not create a frame). The inertia
  /// may be singular (a slender rod, a point mass); a motion nothing resists is refused by the integrator.
  void addBody(const std::string& name, FrameIndex frame, double mass, const Eigen::Vector3d& centre_of_mass,
               const Eigen::Matrix3d& inertia);

  void addJointSpringDamper(const std::string& name, const std::string& joint, double stiffness, double damping,
                            double rest = 0.0);
  void addGuidanceSpring(const std::string& name, const std::string& joint, double stiffness, double damping,
                         TimeFunction target);
  void addPointSpringDamper(const std::string& name, FrameIndex frame_a, const Eigen::Vector3d& point_a,
                            FrameIndex frame_b, const Eigen::Vector3d& point_b, double stiffness, double damping,
                            double rest_length);
  /// A rotational damper (RotationalDamper) of damping c ≥ 0 between frame_a and frame_b.
  void addRotationalDamper(const std::string& name, FrameIndex frame_a, FrameIndex frame_b, double damping);
  void addJointActuation(const std::string& name, const std::string& joint, TimeFunction force);
  /// Track guidance of `frame` by the track of the curve slider `slider_joint` (see TrackGuidance).
  void addTrackGuidance(const std::string& name, FrameIndex frame, const std::string& slider_joint, double stiffness,
                        double damping);
  void setGravity(const Eigen::Vector3d& gravity);
  /// The rotor inertia `inertia` ≥ 0 of joint `joint` (JointArmature), the parameter "JOINT.armature".
  void addArmature(const std::string& joint, double inertia);

  /// Prescribe a joint coordinate as a function of time (exact up to its second derivative).
  void drive(const std::string& joint, TimeFunction motion);

  void addSphericalCut(const std::string& name, FrameIndex frame_a, FrameIndex frame_b);
  void addRevoluteCut(const std::string& name, FrameIndex frame_a, FrameIndex frame_b,
                      const Eigen::Vector3d& axis_in_a, const Eigen::Vector3d& axis_in_b);
  void addWeldCut(const std::string& name, FrameIndex frame_a, FrameIndex frame_b);
  /// Cut curve-sliding joint: frame_a must ride `track` (fixed in frame `base`). Adds the arc length
  /// as a coordinate named `name`, carried by a massless slider from `base`; frame_a is welded to the
  /// slider frame (FollowTrack: 6 equations) or only its origin is held on the curve (Translate: 3).
  void addCurveSliderCut(const std::string& name, FrameIndex frame_a, FrameIndex base, TrackIndex track,
                         SliderOrientation orientation = SliderOrientation::FollowTrack);

  void addSensor(const std::string& name, SensorKind kind);

  // ---- queries ----
  int frameCount() const { return static_cast<int>(frames_.size()); }
  int coordinateCount() const { return static_cast<int>(coordinates_.size()); }
  int constraintCount() const { return constraint_count_; }
  /// Whether every frame moves in the ground's xy plane, at any q: every rotation is about z (revolute
  /// axes ±z, offsets that turn about z, curve sliders, whose tracks lie in the xy plane of their entry
  /// frame) and every translation moves in that plane (prismatic axes without a z component; an offset
  /// may lift a frame out of it, which moves rigidly with it). Angular velocities and accelerations are
  /// then along z and linear ones in the plane, and the recursions (geometry, rates, wrenches, mass
  /// matrix) take their planar paths (3-algorithms/planar_recursions.hpp, mass_matrix.cpp).
  bool planar() const { return planar_; }
  const std::vector<Frame>& frames() const { return frames_; }
  const std::vector<KinematicElement>& elements() const { return elements_; }
  const std::vector<Body>& bodies() const { return bodies_; }
  const std::vector<ForceElement>& forces() const { return forces_; }
  const std::vector<JointArmature>& armatures() const { return armatures_; }
  const std::vector<CutJoint>& cuts() const { return cuts_; }
  const std::vector<ModelTrack>& tracks() const { return tracks_; }
  const Track& track(TrackIndex index) const { return tracks_[static_cast<std::size_t>(index)].geometry; }
  /// A frame a cut joint joins, with the elements on its path from the ground (those that move it):
  /// on_path[k] = 1 for element k on it, 0 for every other element.
  struct CutFramePath {
    FrameIndex frame;
    std::vector<char> on_path;
  };
  /// Those of frame_a then frame_b of each cut, in the order of cuts(); kept from when the cut was
  /// added, as a frame's path never changes.
  const std::vector<CutFramePath>& cutFramePaths() const { return cut_frame_paths_; }
  const std::vector<Sensor>& sensors() const { return sensors_; }
  const std::vector<Coordinate>& coordinates() const { return coordinates_; }
  const std::vector<int>& freeCoordinates() const { return free_; }
  const std::vector<int>& drivenCoordinates() const { return driven_; }
  /// The gravity vector (parameters "gravity.x", "gravity.y", "gravity.z").
  Eigen::Vector3d gravity() const { return vector(gravity_); }
  const ParameterVector3& gravityParameters() const { return gravity_; }

  FrameIndex frame(std::string_view name) const;
  int coordinate(std::string_view name) const;
  int sensor(std::string_view name) const;
  /// The element that owns coordinate i, for error messages.
  const std::string& coordinateOwner(int i) const;

  // ---- parameters: named numbers ("front_secondary.k", "carbody1.mass", "gravity.z", ...) ----
  int parameterCount() const { return static_cast<int>(parameter_values_.size()); }
  /// The names of the parameters, in the order of their indices.
  const std::vector<std::string>& parameterNames() const { return parameter_names_; }
  /// The index of a named parameter; std::invalid_argument when there is none.
  ParameterIndex parameterIndex(std::string_view dotted_name) const;
  double value(ParameterIndex parameter) const { return parameter_values_[static_cast<std::size_t>(parameter)]; }
  Eigen::Vector3d vector(const ParameterVector3& parameters) const;
  /// r(t) of a time input: its parameter when it is constant, its function otherwise.
  /// The order-th time derivative (0, 1, 2) of a time input at t, from the parameters' values.
  double value(const TimeInput& input, double t, int order = 0) const;
  Eigen::Vector3d centreOfMass(const Body& body) const { return vector(body.centre_of_mass); }
  /// The inertia tensor about the centre of mass, in the body frame's axes.
  Eigen::Matrix3d inertia(const Body& body) const;
  double parameter(std::string_view dotted_name) const { return value(parameterIndex(dotted_name)); }
  /// Sets a parameter with the checks of the builder (finite; bodies keep a positive mass and a
  /// positive semi-definite inertia; tracks keep positive lengths and radii); throws std::invalid_argument and leaves the model unchanged otherwise.
  void setParameter(ParameterIndex parameter, double value);
  void setParameter(std::string_view dotted_name, double value) { setParameter(parameterIndex(dotted_name), value); }

 private:
  FrameIndex addElement(const std::string& name, FrameIndex parent, ElementKind kind, bool active);
  /// That `frame` exists and is a frame of the mechanism (not one inside a ball joint).
  void checkFrame(FrameIndex frame, const std::string& who) const;
  void checkNewName(const std::string& name) const;
  /// Records a new cut joint, its constraint rows and its frames' paths.
  void addCut(CutJoint cut, int rows);
  ParameterIndex addParameter(std::string name, double value);
  ParameterVector3 addParameters(const std::string& prefix, const char* const (&suffixes)[3], const Eigen::Vector3d& values);
  TimeInput timeInput(const std::string& name, TimeFunction function);

  std::vector<Frame> frames_;
  std::vector<KinematicElement> elements_;
  std::vector<Body> bodies_;
  std::vector<ForceElement> forces_;
  std::vector<JointArmature> armatures_;
  std::vector<CutJoint> cuts_;
  std::vector<ModelTrack> tracks_;
  std::vector<CutFramePath> cut_frame_paths_;
  std::vector<Sensor> sensors_;
  std::vector<Coordinate> coordinates_;
  std::vector<int> free_, driven_;
  std::vector<std::string> names_;
  std::vector<double> parameter_values_;
  std::vector<std::string> parameter_names_;
  ParameterVector3 gravity_;
  int constraint_count_ = 0;
  bool planar_ = true;  ///< no element added so far moves a frame out of the xy plane
};

/// Number of closure equations of a cut joint.
int equationCount(const CutKind& cut);
/// The frame a of a cut joint, whose axes express its reaction (CutReactionSensor).
FrameIndex cutFrameA(const CutKind& cut);

/// Whether a parameter places frames: a component of an offset's translation or its rotation's angle,
/// a number of a driven joint's motion (drivingCoordinate) or a number of a track (trackOf). The kinematics, the loop
/// closure and the sensors depend on it, not only the forces.
bool isGeometricParameter(const Model& model, ParameterIndex parameter);
/// Whether a geometric parameter moves a frame that a cut joint joins (its offset, its driven joint
/// or a curve slider on its track lies on the path from the ground to one): then the loop closure b(q; b) depends on it.
bool movesLoopClosure(const Model& model, ParameterIndex parameter);
/// The track one of whose numbers `parameter` is, or −1.
int trackOf(const Model& model, ParameterIndex parameter);
/// The driven coordinate whose motion reads `parameter`, or −1.
int drivingCoordinate(const Model& model, ParameterIndex parameter);

/// 0, 1, …, coordinateCount() − 1: every coordinate, driven ones included.
std::vector<int> allCoordinates(const Model& model);

}  // namespace mbsopt
