#include "bench/peer/mujoco_models.hpp"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

namespace peer {

namespace {

using Model = std::unique_ptr<mjModel, decltype(&mj_deleteModel)>;
using Data = std::unique_ptr<mjData, decltype(&mj_deleteData)>;

std::string triple(const std::array<double, 3>& v) {
  std::ostringstream out;
  out.precision(17);
  out << v[0] << ' ' << v[1] << ' ' << v[2];
  return out.str();
}

/// MuJoCo's warnings (an unstable run's) on stderr with the progress lines, not in a MUJOCO_LOG.TXT of
/// the working directory; the run that met one fails (MujocoModel::run).
void warnOnStderr(const char* message) { std::fprintf(stderr, "   mujoco warning: %s\n", message); }

std::string bodyName(int pin) { return pin < 0 ? std::string("world") : "pin" + std::to_string(pin); }

/// The pins nested as MJCF bodies: each at its location in its parent, turned by its initial angle
/// about z, with that angle as the hinge's reference (so qpos is the pin's angle and the compiled
/// pose is the initial one, at which the closures hold and MuJoCo anchors its connects).
void writeBodies(const PinTree& tree, int parent, std::ostringstream& xml) {
  for (std::size_t i = 0; i < tree.pins.size(); ++i) {
    const PinTree::Pin& pin = tree.pins[i];
    if (pin.parent != parent) continue;
    xml.precision(17);
    xml << "<body name='" << bodyName(static_cast<int>(i)) << "' pos='" << triple(pin.location) << "' euler='0 0 "
        << pin.q0 << "'>\n"
        << "<joint name='j" << i << "' type='hinge' axis='0 0 1' ref='" << pin.q0 << "'/>\n"
        << "<inertial pos='" << triple(pin.bar.com) << "' mass='" << pin.bar.mass << "' diaginertia='"
        << triple(pin.bar.inertia) << "'/>\n";
    writeBodies(tree, static_cast<int>(i), xml);
    xml << "</body>\n";
  }
}

}  // namespace

const char* integratorName(MujocoIntegrator integrator) {
  switch (integrator) {
    case MujocoIntegrator::Euler: return "Euler";
    case MujocoIntegrator::Implicit: return "implicit";
    case MujocoIntegrator::RK4: return "RK4";
  }
  return "?";
}

struct MujocoModel::Impl {
  std::string mjcf;
  Model model{nullptr, &mj_deleteModel};
  std::vector<double> q0, u0;  ///< per output, and the start's qpos0 and qvel of every other dof
  std::vector<int> address;  ///< per pin, in the tree's order: its hinge's place in qpos and qvel (MuJoCo's
                             ///< order is the bodies' depth-first order)
  std::vector<double> rates;  ///< a model file's start qvel (its positions start at qpos0); empty for a tree
};

MujocoModel::MujocoModel() : impl_(std::make_unique<Impl>()) { mju_user_warning = warnOnStderr; }
MujocoModel::~MujocoModel() = default;

const std::string& MujocoModel::mjcf() const { return impl_->mjcf; }

std::unique_ptr<MujocoModel> MujocoModel::pinTree(const PinTree& tree, std::string& why) {
  if (!tree.springs.empty() || !tree.torques.empty()) {
    why = "point springs and pin torques are not written as MJCF here";
    return nullptr;
  }
  std::ostringstream xml;
  xml << "<mujoco model='pin_tree'>\n<compiler angle='radian'/>\n<option gravity='" << triple(tree.gravity) << "'/>\n"
      << "<worldbody>\n";
  writeBodies(tree, -1, xml);
  xml << "</worldbody>\n";
  if (!tree.closures.empty()) {
    // As stiff as MuJoCo lets a soft constraint be: the time constant is raised to twice the step.
    xml << "<equality>\n";
    for (const PinTree::Closure& c : tree.closures)
      xml << "<connect body1='" << bodyName(c.a.pin) << "' body2='" << bodyName(c.b.pin) << "' anchor='"
          << triple(c.a.point) << "' solref='0.0001 1' solimp='0.9999 0.9999 0.001 0.5 2'/>\n";
    xml << "</equality>\n";
  }
  xml << "</mujoco>\n";
  std::unique_ptr<MujocoModel> model(new MujocoModel());
  model->impl_->mjcf = xml.str();
  // MuJoCo 2.2.2 compiles from a file or a virtual file system: the latter, in memory.
  const auto vfs = std::make_unique<mjVFS>();  // megabytes of file-name slots: not on the stack
  mj_defaultVFS(vfs.get());
  const std::string& text = model->impl_->mjcf;
  if (mj_makeEmptyFileVFS(vfs.get(), "pin_tree.xml", static_cast<int>(text.size())) != 0)
    throw std::runtime_error("MuJoCo: cannot make the in-memory file");
  const int file = mj_findFileVFS(vfs.get(), "pin_tree.xml");
  std::copy(text.begin(), text.end(), static_cast<char*>(vfs->filedata[file]));
  char error[1000] = "";
  model->impl_->model.reset(mj_loadXML("pin_tree.xml", vfs.get(), error, sizeof error));
  mj_deleteVFS(vfs.get());
  if (!model->impl_->model) throw std::runtime_error(std::string("MuJoCo's compiler: ") + error);
  const mjModel* m = model->impl_->model.get();
  for (std::size_t i = 0; i < tree.pins.size(); ++i) {
    model->impl_->q0.push_back(tree.pins[i].q0);
    model->impl_->u0.push_back(tree.pins[i].u0);
    model->impl_->address.push_back(m->jnt_qposadr[mj_name2id(m, mjOBJ_JOINT, ("j" + std::to_string(i)).c_str())]);
  }
  return model;
}

std::unique_ptr<MujocoModel> MujocoModel::file(const std::string& path, int disable_flags,
                                               const std::vector<std::string>& joints,
                                               const std::vector<std::pair<std::string, double>>& rates) {
  std::unique_ptr<MujocoModel> model(new MujocoModel());
  model->impl_->mjcf = path;
  char error[1000] = "";
  model->impl_->model.reset(mj_loadXML(path.c_str(), nullptr, error, sizeof error));
  if (!model->impl_->model) throw std::runtime_error(std::string("MuJoCo's compiler: ") + error);
  mjModel* m = model->impl_->model.get();
  m->opt.disableflags |= disable_flags;
  const auto joint = [&](const std::string& name) {
    const int id = mj_name2id(m, mjOBJ_JOINT, name.c_str());
    if (id < 0 || m->jnt_type[id] != mjJNT_HINGE) throw std::runtime_error(path + ": no hinge '" + name + "'");
    return id;
  };
  for (const std::string& name : joints) {
    const int id = joint(name);
    model->impl_->address.push_back(m->jnt_qposadr[id]);
    model->impl_->q0.push_back(m->qpos0[m->jnt_qposadr[id]]);
    model->impl_->u0.push_back(0.0);
  }
  model->impl_->rates.assign(static_cast<std::size_t>(m->nv), 0.0);
  for (const auto& [name, rate] : rates) model->impl_->rates[static_cast<std::size_t>(m->jnt_dofadr[joint(name)])] = rate;
  return model;
}

MujocoRun MujocoModel::run(MujocoIntegrator integrator, double step, const std::vector<double>& output_times) const {
  mjModel* m = impl_->model.get();
  m->opt.integrator = integrator == MujocoIntegrator::Euler      ? mjINT_EULER
                      : integrator == MujocoIntegrator::Implicit ? mjINT_IMPLICIT
                                                                 : mjINT_RK4;
  m->opt.timestep = step;
  const Data d(mj_makeData(m), &mj_deleteData);
  const std::vector<int>& address = impl_->address;  // hinges only: qpos and qvel share the addresses
  const bool from_file = !impl_->rates.empty();
  if (from_file) {  // mj_makeData's qpos0 and the rates
    std::copy(impl_->rates.begin(), impl_->rates.end(), d->qvel);
  } else {
    for (std::size_t i = 0; i < address.size(); ++i) {
      d->qpos[address[i]] = impl_->q0[i];
      d->qvel[address[i]] = impl_->u0[i];
    }
  }
  MujocoRun run;
  const auto start = std::chrono::steady_clock::now();
  double t = 0.0;
  for (const double output : output_times) {
    const long steps = std::lround((output - t) / step);
    for (long k = 0; k < steps; ++k) mj_step(m, d.get());
    run.steps += steps;
    t = output;
    std::vector<double> q;  // a file's hinges from their qpos0 (mbsopt's coordinates); a tree's pin angles
    for (std::size_t i = 0; i < address.size(); ++i) q.push_back(d->qpos[address[i]] - (from_file ? impl_->q0[i] : 0.0));
    for (const double angle : q)
      if (!std::isfinite(angle) || d->warning[mjWARN_BADQACC].number > 0) {
        run.message = "MuJoCo: the state is not finite (or its accelerations were bad) at t = " + std::to_string(output) + " s";
        run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        run.outputs.clear();
        return run;
      }
    run.outputs.push_back(std::move(q));
  }
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  run.ok = true;
  return run;
}

std::string mujocoVersion() { return mj_versionString(); }

}  // namespace peer
