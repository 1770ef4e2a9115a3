#include "mbsopt/model/model.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "mbsopt/model/overloaded.hpp"

namespace mbsopt {

namespace {

Eigen::Vector3d unitAxis(const Eigen::Vector3d& axis, const std::string& who) {
  const double norm = axis.norm();
  if (!std::isfinite(norm) || norm < 1e-12) throw std::invalid_argument(who + ": the axis must be a non-zero vector");
  return axis / norm;
}

void checkFinite(double value, const std::string& what) {
  if (!std::isfinite(value)) throw std::invalid_argument(what + " must be finite");
}

/// Empty when (mass, inertia) is a rigid body: positive mass, symmetric inertia with principal
/// moments ≥ 0 that satisfy the triangle inequalities I₁ ≤ I₂ + I₃ (the moments of a real mass
/// distribution: a slender rod has one zero moment, a point mass three); otherwise what is wrong.
/// The eigenvalues carry a round-off of a few ε‖I‖, so both tests allow 1e-12 ‖I‖ of slack.
std::string rigidBodyDefect(double mass, const Eigen::Vector3d& centre_of_mass, const Eigen::Matrix3d& inertia) {
  if (!(mass > 0.0) || !std::isfinite(mass)) return "mass must be positive and finite";
  if (!centre_of_mass.allFinite() || !inertia.allFinite()) return "centre of mass and inertia must be finite";
  if ((inertia - inertia.transpose()).norm() > 1e-9 * std::max(1.0, inertia.norm()))
    return "inertia tensor must be symmetric";
  const Eigen::Vector3d principal = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(inertia).eigenvalues();
  const double slack = 1e-12 * inertia.norm();
  if (!(principal.minCoeff() >= -slack))
    return "inertia tensor must be positive semi-definite (smallest principal moment " +
           std::to_string(principal.minCoeff()) + " < 0)";
  // Ascending order: only the largest can exceed the sum of the other two.
  if (principal[2] > principal[0] + principal[1] + slack)
    return "principal moments of inertia violate the triangle inequality (largest " + std::to_string(principal[2]) +
           " > sum of the other two " + std::to_string(principal[0] + principal[1]) + "): no rigid body has them";
  return {};
}

}  // namespace

int equationCount(const CutKind& cut) {
  return std::visit(Overloaded{[](const SphericalCut&) { return 3; }, [](const RevoluteCut&) { return 5; },
                               [](const WeldCut&) { return 6; }},
                    cut);
}

FrameIndex cutFrameA(const CutKind& cut) {
  return std::visit([](const auto& c) { return c.frame_a; }, cut);
}

namespace {

/// The element whose offset translation or rotation angle `parameter` is, or −1.
int offsetOf(const Model& model, ParameterIndex parameter) {
  const auto& elements = model.elements();
  for (std::size_t k = 0; k < elements.size(); ++k)
    if (const auto* offset = std::get_if<Offset>(&elements[k].kind))
      if (std::find(offset->translation.begin(), offset->translation.end(), parameter) != offset->translation.end() ||
          (offset->turn && offset->turn->angle == parameter))
        return static_cast<int>(k);
  return -1;
}

}  // namespace

int drivingCoordinate(const Model& model, ParameterIndex parameter) {
  for (const int i : model.drivenCoordinates()) {
    const TimeInput& motion = model.coordinates()[static_cast<std::size_t>(i)].motion;
    const bool reads = std::find(motion.coefficients.begin(), motion.coefficients.end(), parameter) !=
                           motion.coefficients.end() ||
                       std::any_of(motion.harmonics.begin(), motion.harmonics.end(), [&](const auto& h) {
                         return std::find(h.begin(), h.end(), parameter) != h.end();
                       });
    if (reads) return i;
  }
  return -1;
}

int trackOf(const Model& model, ParameterIndex parameter) {
  const auto& tracks = model.tracks();
  for (std::size_t i = 0; i < tracks.size(); ++i) {
    const ModelTrack& track = tracks[i];
    if (parameter == track.heading || std::find(track.origin.begin(), track.origin.end(), parameter) != track.origin.end())
      return static_cast<int>(i);
    // Only the numbers a segment has: a straight's second index is unused (not a parameter of it).
    const std::vector<TrackSegmentType>& types = track.geometry.numbers().types;
    for (std::size_t k = 0; k < track.segments.size(); ++k)
      for (int n = 0; n < numberCount(types[k]); ++n)
        if (track.segments[k][static_cast<std::size_t>(n)] == parameter) return static_cast<int>(i);
  }
  return -1;
}

bool isGeometricParameter(const Model& model, ParameterIndex parameter) {
  return offsetOf(model, parameter) >= 0 || drivingCoordinate(model, parameter) >= 0 || trackOf(model, parameter) >= 0;
}

namespace {

/// The elements a geometric parameter moves directly: its offset, its driven joint, or the curve
/// sliders that ride its track.
std::vector<int> elementsPlacedBy(const Model& model, ParameterIndex parameter) {
  if (const int driven = drivingCoordinate(model, parameter); driven >= 0)
    return {model.coordinates()[static_cast<std::size_t>(driven)].element};
  if (const int offset = offsetOf(model, parameter); offset >= 0) return {offset};
  std::vector<int> sliders;
  const int track = trackOf(model, parameter);
  if (track < 0) return sliders;
  const auto& elements = model.elements();
  for (std::size_t k = 0; k < elements.size(); ++k)
    if (const auto* slider = std::get_if<CurveSliderJoint>(&elements[k].kind))
      if (static_cast<int>(slider->track) == track) sliders.push_back(static_cast<int>(k));
  return sliders;
}

}  // namespace

bool movesLoopClosure(const Model& model, ParameterIndex parameter) {
  for (const int element : elementsPlacedBy(model, parameter))
    for (const Model::CutFramePath& path : model.cutFramePaths())
      if (path.on_path[static_cast<std::size_t>(element)]) return true;
  return false;
}

std::vector<int> allCoordinates(const Model& model) {
  std::vector<int> all(static_cast<std::size_t>(model.coordinateCount()));
  std::iota(all.begin(), all.end(), 0);
  return all;
}

Model::Model() {
  frames_.push_back({"ground", -1, 0});
  gravity_ = addParameters("gravity.", {"x", "y", "z"}, Eigen::Vector3d::Zero());
}

ParameterIndex Model::addParameter(std::string name, double value) {
  parameter_names_.push_back(std::move(name));
  parameter_values_.push_back(value);
  return static_cast<ParameterIndex>(parameter_values_.size() - 1);
}

ParameterVector3 Model::addParameters(const std::string& prefix, const char* const (&suffixes)[3],
                                      const Eigen::Vector3d& values) {
  ParameterVector3 out;
  for (int i = 0; i < 3; ++i) out[static_cast<std::size_t>(i)] = addParameter(prefix + suffixes[i], values[i]);
  return out;
}

TimeInput Model::timeInput(const std::string& name, TimeFunction function) {
  TimeInput input;
  if (function.isNumber()) {
    input.coefficients.push_back(addParameter(name, function.value(0.0)));
    return input;
  }
  for (std::size_t k = 0; k < function.coefficients().size(); ++k)
    input.coefficients.push_back(addParameter(name + ".polynomial." + std::to_string(k), function.coefficients()[k]));
  for (std::size_t j = 0; j < function.harmonics().size(); ++j) {
    const TimeFunction::Harmonic& h = function.harmonics()[j];
    const std::string prefix = name + ".harmonics." + std::to_string(j) + ".";
    input.harmonics.push_back({addParameter(prefix + "amplitude", h.amplitude),
                               addParameter(prefix + "angular_frequency", h.angular_frequency),
                               addParameter(prefix + "phase", h.phase)});
  }
  return input;
}

ParameterIndex Model::parameterIndex(std::string_view dotted_name) const {
  const auto found = std::find(parameter_names_.begin(), parameter_names_.end(), dotted_name);
  if (found == parameter_names_.end())
    throw std::invalid_argument("no parameter named '" + std::string(dotted_name) + "'");
  return static_cast<ParameterIndex>(found - parameter_names_.begin());
}

Eigen::Vector3d Model::vector(const ParameterVector3& parameters) const {
  return {value(parameters[0]), value(parameters[1]), value(parameters[2])};
}

double Model::value(const TimeInput& input, double t, int order) const {
  return timeFunctionDerivative<double>(
      input.coefficients.size(), [&](std::size_t k) { return value(input.coefficients[k]); }, input.harmonics.size(),
      [&](std::size_t j, int which) { return value(input.harmonics[j][static_cast<std::size_t>(which)]); }, t, order);
}

Eigen::Matrix3d Model::inertia(const Body& body) const {
  const Eigen::Vector3d moments = vector(body.moments_of_inertia);
  const Eigen::Vector3d& products = body.products_of_inertia;
  Eigen::Matrix3d out;
  out << moments[0], products[0], products[1],  //
      products[0], moments[1], products[2],     //
      products[1], products[2], moments[2];
  return out;
}

void Model::checkFrame(FrameIndex frame, const std::string& who) const {
  if (frame < 0 || frame >= frameCount())
    throw std::invalid_argument(who + ": frame index " + std::to_string(frame) + " does not exist");
  const int element = frames_[static_cast<std::size_t>(frame)].element;
  if (element < 0) return;
  if (const auto* ball = std::get_if<BallJointComponent>(&elements_[static_cast<std::size_t>(element)].kind);
      ball && ball->component < 2) {
    const std::size_t exit = static_cast<std::size_t>(elements_[static_cast<std::size_t>(element + 2 - ball->component)].exit);
    throw std::invalid_argument(who + ": frame '" + frames_[static_cast<std::size_t>(frame)].name +
                                "' lies inside a ball joint, whose exit frame is '" + frames_[exit].name + "'");
  }
}

void Model::checkNewName(const std::string& name) const {
  if (name.empty()) throw std::invalid_argument("every element needs a name");
  if (name.find('.') != std::string::npos)
    throw std::invalid_argument("'" + name + "': names may not contain '.' (it separates parameter names)");
  if (std::find(names_.begin(), names_.end(), name) != names_.end())
    throw std::invalid_argument("the name '" + name + "' is used twice");
}

namespace {

/// Whether an element keeps the motion of a frame in the xy plane of its entry frame (Model::planar).
/// Exact comparisons: an axis a round-off away from z takes the general path, which is always right.
bool movesInPlane(const ElementKind& kind) {
  return std::visit(Overloaded{[](const Offset& o) {
                                 // A turn stays in the plane at every angle only about ±z.
                                 if (o.turn) return o.turn->axis.x() == 0.0 && o.turn->axis.y() == 0.0;
                                 return !o.rotates || (o.rotation(2, 2) == 1.0 && o.rotation(0, 2) == 0.0 &&
                                                       o.rotation(1, 2) == 0.0 && o.rotation(2, 0) == 0.0 &&
                                                       o.rotation(2, 1) == 0.0);
                               },
                               [](const RevoluteJoint& j) { return j.axis.x() == 0.0 && j.axis.y() == 0.0; },
                               [](const PrismaticJoint& j) { return j.axis.z() == 0.0; },
                               [](const CurveSliderJoint&) { return true; },  // its track lies in the plane
                               [](const BallJointComponent&) { return false; }},
                    kind);
}

}  // namespace

FrameIndex Model::addElement(const std::string& name, FrameIndex parent, ElementKind kind, bool active) {
  checkNewName(name);
  const auto* ball = std::get_if<BallJointComponent>(&kind);
  if (!ball || ball->component == 0) checkFrame(parent, name);  // a ball's y and z follow its x inside it
  planar_ = planar_ && movesInPlane(kind);
  names_.push_back(name);
  const int element = static_cast<int>(elements_.size());
  const FrameIndex exit = frameCount();
  int coordinate = -1;
  if (active) {
    coordinate = coordinateCount();
    coordinates_.push_back({name, element, false, {}});
    free_.push_back(coordinate);
  }
  const int before = frames_[static_cast<std::size_t>(parent)].element;  // the element entering `parent`
  const int parent_joint = before < 0 || elements_[static_cast<std::size_t>(before)].coordinate >= 0
                               ? before
                               : elements_[static_cast<std::size_t>(before)].parent_joint;
  const int depth = frames_[static_cast<std::size_t>(parent)].depth + 1;
  elements_.push_back({name, parent, exit, coordinate, std::move(kind), parent_joint});
  frames_.push_back({name, element, depth});
  for (CutFramePath& path : cut_frame_paths_) path.on_path.push_back(0);  // a new element moves no older frame
  return exit;
}

void Model::addCut(CutJoint cut, int rows) {
  for (const FrameIndex frame : cutFrames(cut.kind)) {
    CutFramePath path{frame, std::vector<char>(elements_.size(), 0)};
    for (int k = frames_[static_cast<std::size_t>(frame)].element; k >= 0;) {
      path.on_path[static_cast<std::size_t>(k)] = 1;
      k = frames_[static_cast<std::size_t>(elements_[static_cast<std::size_t>(k)].entry)].element;
    }
    cut_frame_paths_.push_back(std::move(path));
  }
  cuts_.push_back(std::move(cut));
  constraint_count_ += rows;
}

FrameIndex Model::addOffset(const std::string& name, FrameIndex parent, const Eigen::Vector3d& translation,
                            const Eigen::Matrix3d& rotation) {
  if (!translation.allFinite() || !rotation.allFinite()) throw std::invalid_argument(name + ": offset must be finite");
  if ((rotation.transpose() * rotation - Eigen::Matrix3d::Identity()).norm() > 1e-9 || rotation.determinant() < 0.0)
    throw std::invalid_argument(name + ": offset rotation is not a proper rotation matrix");
  checkNewName(name);  // (before its parameters are added: a refused offset leaves none behind)
  checkFrame(parent, name);
  const ParameterVector3 parameters = addParameters(name + ".translation.", {"x", "y", "z"}, translation);
  return addElement(name, parent, Offset{rotation, parameters, rotation != Eigen::Matrix3d::Identity(), std::nullopt}, false);
}

FrameIndex Model::addOffset(const std::string& name, FrameIndex parent, const Eigen::Vector3d& translation,
                            const Eigen::Vector3d& axis, double angle) {
  checkFinite(angle, name + ": rotation angle");
  const Eigen::Vector3d unit = unitAxis(axis, name);
  const Eigen::Matrix3d rotation = Eigen::AngleAxisd(angle, unit).toRotationMatrix();
  if (!translation.allFinite()) throw std::invalid_argument(name + ": offset must be finite");
  checkNewName(name);  // (before its parameters are added: a refused offset leaves none behind)
  checkFrame(parent, name);
  const ParameterVector3 parameters = addParameters(name + ".translation.", {"x", "y", "z"}, translation);
  const OffsetTurn turn{unit, addParameter(name + ".rotation.angle", angle)};
  return addElement(name, parent, Offset{rotation, parameters, true, turn}, false);
}

FrameIndex Model::addRevolute(const std::string& name, FrameIndex parent, const Eigen::Vector3d& axis) {
  return addElement(name, parent, RevoluteJoint{unitAxis(axis, name)}, true);
}

FrameIndex Model::addPrismatic(const std::string& name, FrameIndex parent, const Eigen::Vector3d& axis) {
  return addElement(name, parent, PrismaticJoint{unitAxis(axis, name)}, true);
}

FrameIndex Model::addBallJoint(const std::array<std::string, 3>& names, FrameIndex parent) {
  for (const std::string& name : names) checkNewName(name);  // all three before any is added
  if (names[0] == names[1] || names[0] == names[2] || names[1] == names[2])
    throw std::invalid_argument("the name '" + (names[1] == names[2] ? names[1] : names[0]) + "' is used twice");
  checkFrame(parent, names[0]);
  FrameIndex frame = parent;
  for (int c = 0; c < 3; ++c) frame = addElement(names[static_cast<std::size_t>(c)], frame, BallJointComponent{c}, true);
  return frame;
}

TrackIndex Model::addTrack(const std::string& name, const Track& track) {
  checkNewName(name);
  if (track.segments().empty()) throw std::invalid_argument(name + ": a track needs at least one segment");
  names_.push_back(name);
  const TrackNumbers& numbers = track.numbers();
  ModelTrack added{name, track, addParameters(name + ".origin.", {"x", "y", "z"}, numbers.origin),
                   addParameter(name + ".heading", numbers.heading), {}};
  for (std::size_t k = 0; k < numbers.types.size(); ++k) {
    const TrackSegmentType type = numbers.types[k];
    const std::string prefix = name + ".segments." + std::to_string(k) + ".";
    std::array<ParameterIndex, 2> indices{};
    for (int i = 0; i < numberCount(type); ++i)
      indices[static_cast<std::size_t>(i)] =
          addParameter(prefix + numberName(type, i), numbers.numbers[k][static_cast<std::size_t>(i)]);
    added.segments.push_back(indices);
  }
  tracks_.push_back(std::move(added));
  return static_cast<TrackIndex>(tracks_.size() - 1);
}

FrameIndex Model::addCurveSlider(const std::string& name, FrameIndex parent, TrackIndex track,
                                 SliderOrientation orientation) {
  if (static_cast<std::size_t>(track) >= tracks_.size())
    throw std::invalid_argument(name + ": no track with index " + std::to_string(static_cast<int>(track)));
  return addElement(name, parent, CurveSliderJoint{track, orientation}, true);
}

void Model::addBody(const std::string& name, FrameIndex frame, double mass, const Eigen::Vector3d& centre_of_mass,
                    const Eigen::Matrix3d& inertia) {
  checkNewName(name);
  checkFrame(frame, name);
  if (const std::string defect = rigidBodyDefect(mass, centre_of_mass, inertia); !defect.empty())
    throw std::invalid_argument(name + ": " + defect);
  names_.push_back(name);
  const ParameterIndex mass_parameter = addParameter(name + ".mass", mass);
  const ParameterVector3 com = addParameters(name + ".com.", {"x", "y", "z"}, centre_of_mass);
  const ParameterVector3 moments = addParameters(name + ".", {"Ixx", "Iyy", "Izz"}, inertia.diagonal());
  // rigidBodyDefect accepted the tensor as symmetric: its upper triangle holds the products.
  bodies_.push_back({name, frame, mass_parameter, com, moments, {inertia(0, 1), inertia(0, 2), inertia(1, 2)}});
}

void Model::addJointSpringDamper(const std::string& name, const std::string& joint, double stiffness,
                                 double damping, double rest) {
  addGuidanceSpring(name, joint, stiffness, damping, TimeFunction::constant(rest));
}

void Model::addGuidanceSpring(const std::string& name, const std::string& joint, double stiffness, double damping,
                              TimeFunction target) {
  checkNewName(name);
  checkFinite(stiffness, name + ": stiffness");
  checkFinite(damping, name + ": damping");
  const int i = coordinate(joint);
  names_.push_back(name);
  forces_.push_back(JointSpringDamper{name, i, addParameter(name + ".k", stiffness),
                                      addParameter(name + ".c", damping), timeInput(name + ".rest", std::move(target))});
}

void Model::addArmature(const std::string& joint, double inertia) {
  const int i = coordinate(joint);
  if (!(inertia >= 0.0 && std::isfinite(inertia)))
    throw std::invalid_argument(joint + ": armature must be finite and >= 0, got " + std::to_string(inertia));
  for (const JointArmature& a : armatures_)
    if (a.coordinate == i) throw std::invalid_argument(joint + ": has an armature already");
  armatures_.push_back({i, addParameter(joint + ".armature", inertia)});
}

void Model::addPointSpringDamper(const std::string& name, FrameIndex frame_a, const Eigen::Vector3d& point_a,
                                 FrameIndex frame_b, const Eigen::Vector3d& point_b, double stiffness,
                                 double damping, double rest_length) {
  checkNewName(name);
  checkFrame(frame_a, name);
  checkFrame(frame_b, name);
  checkFinite(stiffness, name + ": stiffness");
  checkFinite(damping, name + ": damping");
  checkFinite(rest_length, name + ": rest length");
  if (!point_a.allFinite() || !point_b.allFinite()) throw std::invalid_argument(name + ": points must be finite");
  names_.push_back(name);
  forces_.push_back(PointSpringDamper{name, frame_a, point_a, frame_b, point_b, addParameter(name + ".k", stiffness),
                                      addParameter(name + ".c", damping),
                                      addParameter(name + ".rest_length", rest_length)});
}

void Model::addRotationalDamper(const std::string& name, FrameIndex frame_a, FrameIndex frame_b, double damping) {
  checkNewName(name);
  checkFrame(frame_a, name);
  checkFrame(frame_b, name);
  checkFinite(damping, name + ": damping");
  names_.push_back(name);
  forces_.push_back(RotationalDamper{name, frame_a, frame_b, addParameter(name + ".c", damping)});
}

void Model::addJointActuation(const std::string& name, const std::string& joint, TimeFunction force) {
  checkNewName(name);
  const int i = coordinate(joint);
  names_.push_back(name);
  forces_.push_back(JointActuation{name, i, timeInput(name + ".value", std::move(force))});
}

void Model::addTrackGuidance(const std::string& name, FrameIndex frame, const std::string& slider_joint,
                             double stiffness, double damping) {
  checkNewName(name);
  checkFrame(frame, name);
  checkFinite(stiffness, name + ": stiffness");
  checkFinite(damping, name + ": damping");
  const int s = coordinate(slider_joint);
  const KinematicElement& slider = elements_[static_cast<std::size_t>(coordinates_[static_cast<std::size_t>(s)].element)];
  if (!std::holds_alternative<CurveSliderJoint>(slider.kind))
    throw std::invalid_argument(name + ": '" + slider_joint + "' is not a curve slider");
  names_.push_back(name);
  forces_.push_back(TrackGuidance{name, frame, s, addParameter(name + ".k", stiffness), addParameter(name + ".c", damping)});
}

void Model::setGravity(const Eigen::Vector3d& gravity) {
  if (!gravity.allFinite()) throw std::invalid_argument("gravity must be finite");
  for (int i = 0; i < 3; ++i) parameter_values_[static_cast<std::size_t>(gravity_[static_cast<std::size_t>(i)])] = gravity[i];
}

void Model::drive(const std::string& joint, TimeFunction motion) {
  const int i = coordinate(joint);
  if (coordinates_[static_cast<std::size_t>(i)].driven) throw std::invalid_argument(joint + " is driven twice");
  coordinates_[static_cast<std::size_t>(i)].driven = true;
  coordinates_[static_cast<std::size_t>(i)].motion = timeInput(joint + ".motion", std::move(motion));
  free_.erase(std::find(free_.begin(), free_.end(), i));
  driven_.push_back(i);
}

void Model::addSphericalCut(const std::string& name, FrameIndex frame_a, FrameIndex frame_b) {
  checkNewName(name);
  checkFrame(frame_a, name);
  checkFrame(frame_b, name);
  if (frame_a == frame_b) throw std::invalid_argument(name + ": a cut joint needs two different frames");
  names_.push_back(name);
  addCut({name, SphericalCut{frame_a, frame_b}}, 3);
}

void Model::addRevoluteCut(const std::string& name, FrameIndex frame_a, FrameIndex frame_b,
                           const Eigen::Vector3d& axis_in_a, const Eigen::Vector3d& axis_in_b) {
  checkNewName(name);
  checkFrame(frame_a, name);
  checkFrame(frame_b, name);
  if (frame_a == frame_b) throw std::invalid_argument(name + ": a cut joint needs two different frames");
  names_.push_back(name);
  addCut({name, RevoluteCut{frame_a, frame_b, unitAxis(axis_in_a, name), unitAxis(axis_in_b, name)}}, 5);
}

void Model::addWeldCut(const std::string& name, FrameIndex frame_a, FrameIndex frame_b) {
  checkNewName(name);
  checkFrame(frame_a, name);
  checkFrame(frame_b, name);
  if (frame_a == frame_b) throw std::invalid_argument(name + ": a cut joint needs two different frames");
  names_.push_back(name);
  addCut({name, WeldCut{frame_a, frame_b}}, 6);
}

void Model::addCurveSliderCut(const std::string& name, FrameIndex frame_a, FrameIndex base, TrackIndex track,
                              SliderOrientation orientation) {
  checkFrame(frame_a, name);
  checkNewName(name);
  checkNewName(name + "_closure");
  const FrameIndex track_point = addCurveSlider(name, base, track, orientation);
  if (orientation == SliderOrientation::FollowTrack) addWeldCut(name + "_closure", frame_a, track_point);
  else addSphericalCut(name + "_closure", frame_a, track_point);
}

void Model::addSensor(const std::string& name, SensorKind kind) {
  if (name.empty()) throw std::invalid_argument("every sensor needs a name");
  if (sensor(name) >= 0) throw std::invalid_argument("the sensor name '" + name + "' is used twice");
  std::visit(Overloaded{[&](const PointSensor& s) {
                          checkFrame(s.frame, name);
                          checkFrame(s.axes, name);
                          if (s.component < 0 || s.component > 2)
                            throw std::invalid_argument(name + ": component must be 0, 1 or 2");
                        },
                        [&](const JointSensor& s) {
                          if (s.coordinate < 0 || s.coordinate >= coordinateCount())
                            throw std::invalid_argument(name + ": no such coordinate");
                        },
                        [&](RelativeAngleSensor& s) {
                          checkFrame(s.frame_a, name);
                          checkFrame(s.frame_b, name);
                          s.axis = unitAxis(s.axis, name);
                        },
                        [&](const EnergySensor&) {},
                        [&](const CutReactionSensor& s) {
                          if (s.cut < 0 || s.cut >= static_cast<int>(cuts_.size()))
                            throw std::invalid_argument(name + ": no such cut joint");
                          if (s.component < 0 || s.component > 2)
                            throw std::invalid_argument(name + ": component must be 0, 1 or 2");
                        }},
             kind);
  sensors_.push_back({name, std::move(kind)});
}

FrameIndex Model::frame(std::string_view name) const {
  for (std::size_t i = 0; i < frames_.size(); ++i)
    if (frames_[i].name == name) return static_cast<FrameIndex>(i);
  throw std::invalid_argument("no frame named '" + std::string(name) + "'");
}

int Model::coordinate(std::string_view name) const {
  for (std::size_t i = 0; i < coordinates_.size(); ++i)
    if (coordinates_[i].name == name) return static_cast<int>(i);
  throw std::invalid_argument("no joint coordinate named '" + std::string(name) + "'");
}

int Model::sensor(std::string_view name) const {
  for (std::size_t i = 0; i < sensors_.size(); ++i)
    if (sensors_[i].name == name) return static_cast<int>(i);
  return -1;
}

const std::string& Model::coordinateOwner(int i) const {
  return elements_[static_cast<std::size_t>(coordinates_[static_cast<std::size_t>(i)].element)].name;
}

void Model::setParameter(ParameterIndex parameter, double value) {
  const auto i = static_cast<std::size_t>(parameter);
  if (i >= parameter_values_.size()) throw std::invalid_argument("no parameter with index " + std::to_string(i));
  const std::string& name = parameter_names_[i];
  if (!std::isfinite(value)) throw std::invalid_argument(name + " must be finite");
  const double previous = parameter_values_[i];
  parameter_values_[i] = value;
  for (KinematicElement& element : elements_)  // a turned offset's rotation follows its angle
    if (auto* offset = std::get_if<Offset>(&element.kind); offset && offset->turn && offset->turn->angle == parameter)
      offset->rotation = Eigen::AngleAxisd(value, offset->turn->axis).toRotationMatrix();
  if (const int track = trackOf(*this, parameter); track >= 0) {  // rebuilt with the builders' checks
    ModelTrack& changed = tracks_[static_cast<std::size_t>(track)];
    TrackNumbers numbers = changed.geometry.numbers();
    numbers.origin = vector(changed.origin);
    numbers.heading = this->value(changed.heading);
    for (std::size_t k = 0; k < changed.segments.size(); ++k)
      for (int n = 0; n < numberCount(numbers.types[k]); ++n)
        numbers.numbers[k][static_cast<std::size_t>(n)] = this->value(changed.segments[k][static_cast<std::size_t>(n)]);
    try {
      changed.geometry = Track(numbers);
    } catch (const std::invalid_argument& e) {
      parameter_values_[i] = previous;
      throw std::invalid_argument(name + " = " + std::to_string(value) + " leaves track '" + changed.name +
                                  "' invalid: " + e.what());
    }
  }
  for (const JointArmature& a : armatures_)
    if (a.inertia == parameter && value < 0.0) {
      parameter_values_[i] = previous;
      throw std::invalid_argument(name + " = " + std::to_string(value) + ": an armature must be >= 0");
    }
  for (const Body& body : bodies_) {  // the same checks as addBody
    if (const std::string defect = rigidBodyDefect(this->value(body.mass), centreOfMass(body), inertia(body));
        !defect.empty()) {
      parameter_values_[i] = previous;
      throw std::invalid_argument(name + " = " + std::to_string(value) + " leaves body '" + body.name +
                                  "' invalid: " + defect);
    }
  }
}

}  // namespace mbsopt
