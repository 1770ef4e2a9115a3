// Compiled as C++17: see simbody_models.hpp.
#include "bench/peer/simbody_models.hpp"

#include <Simbody.h>

#include <chrono>
#include <cmath>
#include <exception>
#include <functional>
#include <stdexcept>

namespace peer {

using namespace SimTK;

const char* integratorName(SimbodyIntegrator integrator) {
  switch (integrator) {
    case SimbodyIntegrator::RungeKuttaFeldberg: return "RungeKuttaFeldberg";
    case SimbodyIntegrator::RungeKuttaMerson: return "RungeKuttaMerson";
    case SimbodyIntegrator::CPodes: return "CPodes";
  }
  return "?";
}

struct SimbodyModel::Impl {
  MultibodySystem system;
  SimbodyMatterSubsystem matter{system};
  GeneralForceSubsystem forces{system};
  std::vector<MobilizedBodyIndex> pins;  ///< one per coordinate, in the comparison's order
  State initial;
};

SimbodyModel::SimbodyModel() : impl_(std::make_unique<Impl>()) {}
SimbodyModel::~SimbodyModel() = default;

int SimbodyModel::coordinateCount() const { return static_cast<int>(impl_->pins.size()); }

namespace {

Body::Rigid rigid(const Bar& bar) {
  const Vec3 com(bar.com[0], bar.com[1], bar.com[2]);
  const Inertia about_com(bar.inertia[0], bar.inertia[1], bar.inertia[2]);
  return Body::Rigid(MassProperties(bar.mass, com, about_com.shiftFromMassCenter(com, bar.mass)));
}

Bar uniformBar(double length, double mass) {
  const double i = mass * length * length / 12.0;
  return Bar{mass, {0.5 * length, 0.0, 0.0}, {i, i, i}};
}

Vec3 vec3(const std::array<double, 3>& v) { return Vec3(v[0], v[1], v[2]); }

/// Holds the point `point_b` of body b on the point `point_a` of body a, in the plane z = const: two
/// PointInPlane constraints, whose planes (normals x and y of a's frame) meet in the line through
/// point_a along z.
void pinPoints(MobilizedBody& a, const Vec3& point_a, MobilizedBody& b, const Vec3& point_b) {
  Constraint::PointInPlane(a, UnitVec3(1, 0, 0), point_a[0], b, point_b);
  Constraint::PointInPlane(a, UnitVec3(0, 1, 0), point_a[1], b, point_b);
}

}  // namespace

std::unique_ptr<SimbodyModel> SimbodyModel::fourBar(const Bar& crank_bar, const Bar& coupler_bar,
                                                    const Bar& rocker_bar) {
  std::unique_ptr<SimbodyModel> model(new SimbodyModel());
  Impl& m = *model->impl_;
  Force::UniformGravity(m.forces, m.matter, Vec3(0, -9.81, 0));
  MobilizedBody::Pin crank(m.matter.Ground(), Transform(), rigid(crank_bar), Transform());
  MobilizedBody::Pin coupler(crank, Transform(Vec3(0.4, 0, 0)), rigid(coupler_bar), Transform());
  MobilizedBody::Pin rocker(m.matter.Ground(), Transform(Vec3(1.0, 0, 0)), rigid(rocker_bar), Transform());
  pinPoints(rocker, Vec3(0.8, 0, 0), coupler, Vec3(1.0, 0, 0));
  m.pins = {crank.getMobilizedBodyIndex(), coupler.getMobilizedBodyIndex(), rocker.getMobilizedBodyIndex()};
  m.initial = m.system.realizeTopology();
  crank.setOneQ(m.initial, 0, 0.0);
  coupler.setOneQ(m.initial, 0, std::acos(0.6));  // the 3-4-5 triangle of four_bar.yaml
  rocker.setOneQ(m.initial, 0, 0.5 * Pi);
  return model;
}

std::unique_ptr<SimbodyModel> SimbodyModel::chain(int links, double length, double mass) {
  std::unique_ptr<SimbodyModel> model(new SimbodyModel());
  Impl& m = *model->impl_;
  Force::UniformGravity(m.forces, m.matter, Vec3(0, -9.81, 0));
  MobilizedBody parent = m.matter.Ground();
  for (int i = 0; i < links; ++i) {
    MobilizedBody::Pin link(parent, Transform(Vec3(i == 0 ? 0.0 : length, 0, 0)), rigid(uniformBar(length, mass)),
                            Transform());
    m.pins.push_back(link.getMobilizedBodyIndex());
    parent = link;
  }
  m.initial = m.system.realizeTopology();  // q = 0: horizontal, at rest
  return model;
}

std::unique_ptr<SimbodyModel> SimbodyModel::nFourBar(int n, double rocker_angle, double rocker_rate) {
  std::unique_ptr<SimbodyModel> model(new SimbodyModel());
  Impl& m = *model->impl_;
  Force::UniformGravity(m.forces, m.matter, Vec3(0, -9.81, 0));
  std::vector<MobilizedBody::Pin> rockers, couplers;
  for (int i = 0; i <= n; ++i)
    rockers.emplace_back(m.matter.Ground(), Transform(Vec3(i, 0, 0)), rigid(uniformBar(1.0, 1.0)), Transform());
  for (int i = 0; i < n; ++i) {
    couplers.emplace_back(rockers[i], Transform(Vec3(1.0, 0, 0)), rigid(uniformBar(1.0, 1.0)), Transform());
    pinPoints(rockers[i + 1], Vec3(1.0, 0, 0), couplers[i], Vec3(1.0, 0, 0));
  }
  for (auto& r : rockers) m.pins.push_back(r.getMobilizedBodyIndex());
  for (auto& c : couplers) m.pins.push_back(c.getMobilizedBodyIndex());
  m.initial = m.system.realizeTopology();
  for (auto& r : rockers) {
    r.setOneQ(m.initial, 0, rocker_angle);
    r.setOneU(m.initial, 0, rocker_rate);
  }
  for (auto& c : couplers) {  // horizontal, translating
    c.setOneQ(m.initial, 0, -rocker_angle);
    c.setOneU(m.initial, 0, -rocker_rate);
  }
  return model;
}

std::unique_ptr<SimbodyModel> SimbodyModel::pinTree(const PinTree& tree) {
  std::unique_ptr<SimbodyModel> model(new SimbodyModel());
  Impl& m = *model->impl_;
  if (vec3(tree.gravity) != Vec3(0)) Force::UniformGravity(m.forces, m.matter, vec3(tree.gravity));
  // A pin's body, built on first use after its parent's (the list's order is the comparison's, not the tree's).
  std::vector<MobilizedBody> pins(tree.pins.size());  // empty handles until built
  const std::function<MobilizedBody(int)> body = [&](int index) {
    if (index < 0) return MobilizedBody(m.matter.Ground());
    const PinTree::Pin& pin = tree.pins.at(index);
    if (pins[index].isEmptyHandle()) {
      MobilizedBody parent = body(pin.parent);
      pins[index] = MobilizedBody::Pin(parent, Transform(vec3(pin.location)), rigid(pin.bar), Transform());
    }
    return pins[index];
  };
  for (std::size_t i = 0; i < pins.size(); ++i) m.pins.push_back(body(static_cast<int>(i)).getMobilizedBodyIndex());
  for (const PinTree::Closure& closure : tree.closures) {
    MobilizedBody a = body(closure.a.pin), b = body(closure.b.pin);
    pinPoints(a, vec3(closure.a.point), b, vec3(closure.b.point));
  }
  for (const PinTree::Spring& spring : tree.springs)
    Force::TwoPointLinearSpring(m.forces, body(spring.a.pin), vec3(spring.a.point), body(spring.b.pin),
                                vec3(spring.b.point), spring.stiffness, spring.rest_length);
  for (const PinTree::Torque& torque : tree.torques)
    Force::MobilityConstantForce(m.forces, pins.at(torque.pin), MobilizerUIndex(0), torque.value);
  m.initial = m.system.realizeTopology();
  for (std::size_t i = 0; i < pins.size(); ++i) {
    pins[i].setOneQ(m.initial, 0, tree.pins[i].q0);
    pins[i].setOneU(m.initial, 0, tree.pins[i].u0);
  }
  State check = m.initial;
  m.system.realize(check, Stage::Position);
  const double gap = check.getQErr().normInf();
  if (!(gap <= 1e-12))
    throw std::runtime_error("PinTree: the initial angles leave a closure open by " + String(gap) + " m");
  return model;
}

SimbodyRun SimbodyModel::run(SimbodyIntegrator kind, double accuracy, const std::vector<double>& output_times,
                             double max_seconds) const {
  const Impl& m = *impl_;
  SimbodyRun result;
  const auto start = std::chrono::steady_clock::now();
  std::unique_ptr<Integrator> integrator;
  try {
    switch (kind) {
      case SimbodyIntegrator::RungeKuttaFeldberg: integrator.reset(new RungeKuttaFeldbergIntegrator(m.system)); break;
      case SimbodyIntegrator::RungeKuttaMerson: integrator.reset(new RungeKuttaMersonIntegrator(m.system)); break;
      case SimbodyIntegrator::CPodes: integrator.reset(new CPodesIntegrator(m.system)); break;
    }
    integrator->setAccuracy(accuracy);  // the constraint tolerance follows it (Simbody's default)
    integrator->setAllowInterpolation(false);
    integrator->setInternalStepLimit(1000);  // return now and then, to watch the time budget
    integrator->initialize(m.initial);
    result.outputs.reserve(output_times.size());
    for (double t : output_times) {
      for (;;) {
        const Integrator::SuccessfulStepStatus status = integrator->stepTo(t);
        if (integrator->isSimulationOver())
          throw std::runtime_error("the integrator ended the simulation at t = " +
                                   std::to_string(integrator->getTime()) + ": " +
                                   Integrator::getTerminationReasonString(integrator->getTerminationReason()));
        if (status == Integrator::ReachedReportTime && integrator->getTime() >= t) break;
        const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        if (elapsed > max_seconds)
          throw std::runtime_error("gave up after " + std::to_string(elapsed) + " s (budget) at t = " +
                                   std::to_string(integrator->getTime()) + ", " +
                                   std::to_string(integrator->getNumStepsTaken()) + " steps");
      }
      const State& state = integrator->getState();
      if (std::abs(state.getTime() - t) > 1e-9 * (1.0 + t))
        throw std::runtime_error("reported t = " + std::to_string(state.getTime()) + " instead of " + std::to_string(t));
      std::vector<double> q;
      q.reserve(m.pins.size());
      for (MobilizedBodyIndex pin : m.pins) q.push_back(m.matter.getMobilizedBody(pin).getOneQ(state, MobilizerQIndex(0)));
      result.outputs.push_back(std::move(q));
    }
    result.ok = true;
  } catch (const std::exception& error) {
    result.ok = false;
    result.message = error.what();
    result.outputs.clear();
  }
  if (integrator) {
    result.steps = integrator->getNumStepsTaken();
    result.step_attempts = integrator->getNumStepsAttempted();
    result.realizations = integrator->getNumRealizations();
    result.projections = integrator->getNumProjections();
  }
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

std::string simbodyVersion() {
  int major = 0, minor = 0, build = 0;
  SimTK_version_simbody(&major, &minor, &build);
  return std::to_string(major) + "." + std::to_string(minor) + (build ? "." + std::to_string(build) : "");
}

}  // namespace peer
