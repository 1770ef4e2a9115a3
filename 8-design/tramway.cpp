#include "mbsopt/design/tramway.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace mbsopt {

namespace {

// Vehicle data of the spec (docs/tramway.md). In the yaw plane only I_zz acts; the other
// principal moments are set equal to it so the tensor is a valid one.
constexpr double kBogieMass = 4500.0, kBogieYawInertia = 3500.0;
constexpr double kCarbodyMass = 12000.0, kCarbodyYawInertia = 1.0e5;
constexpr double kGuidanceStiffness = 2.0e6, kGuidanceDamping = 2.0e4;
constexpr double kNose = 5.0, kFrontPivot = -0.5, kFrontArticulation = -5.0;  // carbody 1, from its CoM
constexpr double kRearArticulation = 5.0, kRearPivot = 0.5;                    // carbody 2, from its CoM

const Eigen::Vector3d kUp = Eigen::Vector3d::UnitZ();

Eigen::Matrix3d isotropic(double inertia) { return inertia * Eigen::Matrix3d::Identity(); }

}  // namespace

Track tramwayTrack(const TramwayOptions& options) {
  using tramway::kRadius;
  const double turn = options.arc_angle;
  const double Lt = options.transition_length;
  if (!(turn > 0.0) || !std::isfinite(turn)) throw std::invalid_argument("tramway: the arc angle must be positive");
  if (!(Lt >= 0.0 && Lt < kRadius * turn))
    throw std::invalid_argument("tramway: the transition length must lie in [0, R·angle) = [0, " +
                                std::to_string(kRadius * turn) + ") m so that the two clothoids leave an arc");
  Track track;
  track.straight(tramway::kFirstStraight);
  if (Lt > 0.0) {
    // Each clothoid turns L_t / (2R); the arc keeps the rest of the turn.
    track.clothoid(Lt, 1.0 / kRadius).arc(kRadius, turn - Lt / kRadius).clothoid(Lt, 0.0);
  } else {
    track.arc(kRadius, turn);
  }
  track.straight(tramway::kLastStraight);
  return track;
}

Scene tramwayScene(const TramwayDesign& design, const TramwayOptions& options) {
  Scene scene;
  Model& m = scene.model;
  const TrackIndex track = m.addTrack("rail", tramwayTrack(options));
  const Eigen::Vector3d x = Eigen::Vector3d::UnitX();

  const bool relative = options.chart == BogieYawChart::RelativeToTrack;
  const SliderOrientation sliders = relative ? SliderOrientation::FollowTrack : SliderOrientation::Translate;

  // ground → curve slider (s₁, driven) → bogie-1 yaw → bogie 1
  const FrameIndex track_point_1 = m.addCurveSlider("bogie1_track", Model::ground, track, sliders);
  const FrameIndex bogie1 = m.addRevolute("bogie1_yaw", track_point_1, kUp);
  m.addBody("bogie1", bogie1, kBogieMass, Eigen::Vector3d::Zero(), isotropic(kBogieYawInertia));
  if (relative) m.addJointSpringDamper("bogie1_guidance", "bogie1_yaw", kGuidanceStiffness, kGuidanceDamping);
  else m.addTrackGuidance("bogie1_guidance", bogie1, "bogie1_track", kGuidanceStiffness, kGuidanceDamping);
  m.drive("bogie1_track", TimeFunction::polynomial({tramway::kStartArcLength, options.speed}));

  // → front secondary (pivot at the bogie centre) → carbody 1
  const FrameIndex carbody1_pivot = m.addRevolute("front_pivot", bogie1, kUp);
  const FrameIndex carbody1 = m.addOffset("carbody1_centre", carbody1_pivot, -kFrontPivot * x);
  m.addBody("carbody1", carbody1, kCarbodyMass, Eigen::Vector3d::Zero(), isotropic(kCarbodyYawInertia));
  m.addJointSpringDamper("front_secondary", "front_pivot", design.front_stiffness, design.front_damping);

  // → articulation → carbody 2
  const FrameIndex articulation_point = m.addOffset("articulation_point", carbody1, kFrontArticulation * x);
  const FrameIndex carbody2_joint = m.addRevolute("articulation", articulation_point, kUp);
  const FrameIndex carbody2 = m.addOffset("carbody2_centre", carbody2_joint, -kRearArticulation * x);
  m.addBody("carbody2", carbody2, kCarbodyMass, Eigen::Vector3d::Zero(), isotropic(kCarbodyYawInertia));

  // → rear secondary → bogie 2 → [bogie-2 yaw] → cut curve slider (s₂) back to the track
  const FrameIndex rear_pivot_point = m.addOffset("rear_pivot_point", carbody2, kRearPivot * x);
  const FrameIndex bogie2 = m.addRevolute("rear_pivot", rear_pivot_point, kUp);
  m.addBody("bogie2", bogie2, kBogieMass, Eigen::Vector3d::Zero(), isotropic(kBogieYawInertia));
  m.addJointSpringDamper("rear_secondary", "rear_pivot", design.rear_stiffness, design.rear_damping);
  if (relative) {
    const FrameIndex bogie2_on_track = m.addRevolute("bogie2_yaw", bogie2, kUp);
    m.addJointSpringDamper("bogie2_guidance", "bogie2_yaw", kGuidanceStiffness, kGuidanceDamping);
    m.addCurveSliderCut("bogie2_track", bogie2_on_track, Model::ground, track, SliderOrientation::FollowTrack);
  } else {
    m.addCurveSliderCut("bogie2_track", bogie2, Model::ground, track, SliderOrientation::Translate);
    m.addTrackGuidance("bogie2_guidance", bogie2, "bogie2_track", kGuidanceStiffness, kGuidanceDamping);
  }

  // Responses of the spec.
  m.addSensor("a_lat", PointSensor{carbody1, kNose * x, Derivative::Acceleration, carbody1, 1});
  m.addSensor("yaw_front", RelativeAngleSensor{bogie1, carbody1, kUp});
  m.addSensor("yaw_rear", RelativeAngleSensor{bogie2, carbody2, kUp});

  // Initial state: straight, aligned with +x, bogie 1 at s = 10 m, everything at 3.7 m/s, springs at rest.
  const Eigen::Index n = m.coordinateCount();
  scene.q0 = Eigen::VectorXd::Zero(n);
  scene.v0 = Eigen::VectorXd::Zero(n);
  scene.q0[m.coordinate("bogie1_track")] = tramway::kStartArcLength;
  scene.q0[m.coordinate("bogie2_track")] = tramway::kStartArcLength - tramway::kBogieSpacing;
  scene.v0[m.coordinate("bogie1_track")] = options.speed;
  scene.v0[m.coordinate("bogie2_track")] = options.speed;
  scene.settings.step = 1e-3;
  scene.settings.end_time = tramway::kEndTime;
  return scene;
}

DesignProblem tramwayDesignProblem(const TramwayDesign& design, const TramwayOptions& options) {
  DesignProblem problem{tramwayScene(design, options), {}, {}};
  DesignDescription& d = problem.design;
  // Scales of 100 kN·m/rad and 10 kN·m·s/rad put every variable between 0.5 and 10, like b5 (README:
  // in kN units, 50 to 1000 beside b5 ≈ 2, SLSQP's identity start of its BFGS Hessian stalls it).
  const Model& model = problem.scene.model;
  for (const char* spring : {"front_secondary.k", "rear_secondary.k"})
    d.variables.push_back(designVariable(model, spring, 50e3, 1000e3, 100e3));
  for (const char* damper : {"front_secondary.c", "rear_secondary.c"})
    d.variables.push_back(designVariable(model, damper, 5e3, 50e3, 10e3));
  d.cost = {"a_lat", ResponseMeasure::MaxAbs};
  d.artificial = {3.0, 0.0, 10.0, 1.0};
  const double ten_degrees = 10.0 / 180.0 * std::numbers::pi;
  d.constraints = {{"yaw_front", ResponseMeasure::MaxAbs, ten_degrees, false, std::nullopt},
                   {"yaw_rear", ResponseMeasure::MaxAbs, ten_degrees, false, std::nullopt}};
  d.transcription.measure = TimeMeasure::PositivePart;  // the paper's ∫⟨φ⟩dt (15)-(16)
  return problem;
}

}  // namespace mbsopt
