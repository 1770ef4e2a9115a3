#include "mbsopt/io/model_file.hpp"

#include <mujoco/mujoco.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <memory>
#include <regex>
#include <sstream>

#include "mbsopt/io/scene_file.hpp"

namespace mbsopt {

namespace {

using MujocoModel = std::unique_ptr<mjModel, decltype(&mj_deleteModel)>;

/// The file's text, for the lines of the elements it names.
std::string fileText(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

/// 1-based line of the first element among `tags` whose name is `name`, or of the first among them
/// at all when `name` is empty (an element the file leaves unnamed); 0 when none is found (an element
/// of an included file).
int lineOf(const std::string& text, std::initializer_list<const char*> tags, const std::string& name) {
  std::string alternatives;
  for (const char* tag : tags) alternatives += (alternatives.empty() ? "" : "|") + std::string(tag);
  std::string escaped;
  for (const char c : name) {
    if (std::string("\\^$.|?*+()[]{}").find(c) != std::string::npos) escaped += '\\';
    escaped += c;
  }
  const std::regex element(name.empty() ? "<(" + alternatives + ")\\b"
                                         : "<(" + alternatives + ")\\b[^>]*\\bname\\s*=\\s*[\"']" + escaped + "[\"']");
  std::smatch match;
  if (!std::regex_search(text, match, element)) return 0;
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + match.position(0), '\n'));
}

Eigen::Matrix3d rotationOf(const mjtNum* quaternion) {  // MuJoCo's (w, x, y, z)
  return Eigen::Quaterniond(quaternion[0], quaternion[1], quaternion[2], quaternion[3]).normalized().toRotationMatrix();
}

Eigen::Vector3d vectorOf(const mjtNum* v) { return {v[0], v[1], v[2]}; }

class ModelFileReader {
 public:
  ModelFileReader(Model& model, const std::string& path, const std::vector<std::string>& ignore)
      : model_(model), path_(path), text_(fileText(path)), mj_(compile(path), &mj_deleteModel), ignore_(ignore) {
    for (const std::string& feature : ignore_)
      if (std::find(modelFileFeatures().begin(), modelFileFeatures().end(), feature) == modelFileFeatures().end()) {
        std::string names;
        for (const std::string& f : modelFileFeatures()) names += (names.empty() ? "" : ", ") + f;
        throw SceneError(path_, 0, 0, "ignore: '" + feature + "' is not a feature a model file may leave out (" + names + ")");
      }
  }

  ModelFileContents read() {
    checkFeatures();
    const mjModel& m = *mj_;
    // The file's own switches: gravity and passive forces (springs, dampers) may be off in it.
    model_.setGravity(m.opt.disableflags & mjDSBL_GRAVITY ? Eigen::Vector3d::Zero() : vectorOf(m.opt.gravity));
    frames_.assign(static_cast<std::size_t>(m.nbody), Model::ground);
    for (int b = 1; b < m.nbody; ++b) addBody(b);
    return std::move(contents_);
  }

 private:
  static mjModel* compile(const std::string& path) {
    std::array<char, 1000> error{};
    mjModel* compiled = mj_loadXML(path.c_str(), nullptr, error.data(), static_cast<int>(error.size()));
    if (compiled) return compiled;
    std::string message(error.data());
    int line = 0;
    std::smatch match;
    if (std::regex_search(message, match, std::regex("line\\s*=?\\s*(\\d+)"))) line = std::stoi(match[1].str());
    std::replace(message.begin(), message.end(), '\n', ' ');
    throw SceneError(path, line, 0, "MuJoCo's compiler: " + message);
  }

  bool ignored(const std::string& feature) const {
    return std::find(ignore_.begin(), ignore_.end(), feature) != ignore_.end();
  }

  std::string name(int type, int id, const char* kind) const {
    const std::string given = fileName(type, id);
    return given.empty() ? std::string(kind) + std::to_string(id) : given;
  }

  /// The name the file gives the element, empty when it gives none.
  std::string fileName(int type, int id) const {
    const char* n = mj_id2name(mj_.get(), type, id);
    return n ? std::string(n) : std::string();
  }

  /// Refused at `line` unless `feature` is ignored; then listed once in left_out.
  void feature(const std::string& feature, int count, const std::string& first, int line, const std::string& why) {
    if (count == 0) return;
    if (!ignored(feature))
      throw SceneError(path_, line, 0,
                       first + ": " + why + "; mbsopt does not model " + feature + " (a scene's `model: {ignore: [" +
                           feature + "]}` leaves them out)");
    contents_.left_out.push_back(feature + ": " + std::to_string(count) + " left out, the first " + first);
  }

  void checkFeatures() {
    const mjModel& m = *mj_;
    // Contacts: a geom that may collide, unless the file itself switches contacts off.
    if (!(m.opt.disableflags & mjDSBL_CONTACT)) {
      int count = 0, first = -1;
      for (int g = 0; g < m.ngeom; ++g)
        if (m.geom_contype[g] != 0 || m.geom_conaffinity[g] != 0) {
          ++count;
          if (first < 0) first = g;
        }
      if (m.npair > 0) count += m.npair;
      if (count > 0) {
        const std::string geom = first >= 0 ? name(mjOBJ_GEOM, first, "geom") : "contact pair 0";
        feature("contacts", count, "geom '" + geom + "'", lineOf(text_, {"geom", "collision"}, geom),
                "it may touch other geoms (contype/conaffinity ≠ 0)");
      }
    }
    auto firstOf = [](int n, auto&& has) {
      int count = 0, first = -1;
      for (int i = 0; i < n; ++i)
        if (has(i)) {
          ++count;
          if (first < 0) first = i;
        }
      return std::pair{count, first};
    };
    if (!(m.opt.disableflags & mjDSBL_LIMIT)) {
      const auto [count, first] = firstOf(m.njnt, [&](int j) { return m.jnt_limited[j] != 0; });
      if (count > 0) {
        const std::string joint = name(mjOBJ_JOINT, first, "joint");
        feature("limits", count, "joint '" + joint + "'", lineOf(text_, {"joint", "freejoint"}, joint),
                "it is limited to a range");
      }
    }
    if (m.nu > 0 && !(m.opt.disableflags & mjDSBL_ACTUATION)) {
      const std::string actuator = name(mjOBJ_ACTUATOR, 0, "actuator");
      feature("actuators", m.nu, "actuator '" + actuator + "'",
              lineOf(text_, {"motor", "general", "position", "velocity", "cylinder", "muscle", "adhesion", "transmission"},
                     actuator),
              "it drives the model by a control input");
    }
    if (m.ntendon > 0) {
      const std::string tendon = name(mjOBJ_TENDON, 0, "tendon");
      feature("tendons", m.ntendon, "tendon '" + tendon + "'", lineOf(text_, {"spatial", "fixed"}, tendon),
              "it couples joints or sites");
    }
    if (const auto [count, first] = firstOf(m.nv, [&](int d) { return m.dof_frictionloss[d] != 0.0; });
        count > 0 && !(m.opt.disableflags & mjDSBL_FRICTIONLOSS)) {
      const std::string joint = name(mjOBJ_JOINT, m.dof_jntid[first], "joint");
      feature("friction_loss", count, "joint '" + joint + "'", lineOf(text_, {"joint", "freejoint"}, joint),
              "it has dry friction (frictionloss)");
    }
    // A free joint's or a ball's armature is on its angular velocity's components, a rotor term
    // J(φ)ᵀ diag(armature) J(φ) in its rotation vector's rates: refused there, taken on hinges and slides.
    if (const auto [count, first] = firstOf(m.nv, [&](int d) {
          const int type = m.jnt_type[m.dof_jntid[d]];
          return m.dof_armature[d] != 0.0 && (type == mjJNT_FREE || type == mjJNT_BALL);
        });
        count > 0) {
      const std::string joint = name(mjOBJ_JOINT, m.dof_jntid[first], "joint");
      feature("armature", count, "joint '" + joint + "'", lineOf(text_, {"joint", "freejoint"}, joint),
              "a free or ball joint with a rotor inertia (armature) on its rotation");
    }
    // Refused outright: `id`, of `type`, is the first such element (located by its name, or as the
    // first of `tags` after `<section` when the file leaves it unnamed and names a section).
    const auto refuse = [&](bool present, int type, int id, const char* kind, const std::string& what,
                            std::initializer_list<const char*> tags, const std::string& section) {
      if (!present) return;
      const std::string given = fileName(type, id);
      int line = 0;
      if (!given.empty()) {
        line = lineOf(text_, tags, given);
      } else if (const std::size_t start = section.empty() ? std::string::npos : text_.find("<" + section);
                 start != std::string::npos) {
        const int in_section = lineOf(text_.substr(start), tags, "");
        if (in_section > 0) line = in_section + static_cast<int>(std::count(text_.begin(), text_.begin() + static_cast<long>(start), '\n'));
      }
      throw SceneError(path_, line, 0,
                       std::string(kind) + " '" + name(type, id, kind) + "': " + what +
                           ", which mbsopt does not read from a model file");
    };
    refuse(m.neq > 0 && !(m.opt.disableflags & mjDSBL_EQUALITY), mjOBJ_EQUALITY, 0, "equality",
           "an equality constraint", {"connect", "weld", "joint", "tendon", "distance"}, "equality");
    int mocap = 0;
    while (mocap < m.nbody && m.body_mocapid[mocap] < 0) ++mocap;
    refuse(m.nmocap > 0, mjOBJ_BODY, mocap, "body", "a mocap body (moved by the user, not the dynamics)", {"body"},
           "");  // unnamed: the file only (the first body of the file need not be it)
    if (m.opt.density != 0.0 || m.opt.viscosity != 0.0 || vectorOf(m.opt.wind).norm() != 0.0)
      throw SceneError(path_, lineOf(text_, {"option"}, ""), 0,
                       "option: density, viscosity or wind ≠ 0 (fluid forces), which mbsopt does not model");
  }

  /// B_placement, the joints about their anchors, B_frame; the body B on it.
  void addBody(int b) {
    const mjModel& m = *mj_;
    const std::string body = name(mjOBJ_BODY, b, "body");
    const int line = lineOf(text_, {"body", "link"}, body);
    const auto guarded = [&](auto&& call) {
      try {
        return call();
      } catch (const std::invalid_argument& e) {
        throw SceneError(path_, line, 0, "body '" + body + "': " + e.what());
      }
    };
    const FrameIndex parent = frames_[static_cast<std::size_t>(m.body_parentid[b])];
    const bool free = m.body_jntnum[b] == 1 && m.jnt_type[m.body_jntadr[b]] == mjJNT_FREE;
    // A free joint places the body in the ground's axes itself (MuJoCo ignores pos and quat there).
    FrameIndex frame = guarded([&] {
      return free ? model_.addOffset(added(body + "_placement"), parent, Eigen::Vector3d::Zero())
                  : model_.addOffset(added(body + "_placement"), parent, vectorOf(m.body_pos + 3 * b),
                                     rotationOf(m.body_quat + 4 * b));
    });
    Eigen::Vector3d anchor = Eigen::Vector3d::Zero();  // of the last joint, in the body's axes
    for (int j = m.body_jntadr[b]; j >= 0 && j < m.body_jntadr[b] + m.body_jntnum[b]; ++j)
      frame = guarded([&] { return addJoint(j, frame, anchor); });
    const Eigen::Vector3d back = anchor.isZero() ? Eigen::Vector3d::Zero() : Eigen::Vector3d(-anchor);  // no −0
    frame = guarded([&] { return model_.addOffset(added(body + "_frame"), frame, back); });
    frames_[static_cast<std::size_t>(b)] = frame;
    if (m.body_mass[b] == 0.0 && vectorOf(m.body_inertia + 3 * b).isZero()) return;
    const Eigen::Matrix3d R = rotationOf(m.body_iquat + 4 * b);
    const Eigen::Matrix3d inertia = R * vectorOf(m.body_inertia + 3 * b).asDiagonal() * R.transpose();
    guarded([&] { model_.addBody(added(body), frame, m.body_mass[b], vectorOf(m.body_ipos + 3 * b), inertia); });
  }

  /// Joint j after `frame`, about its anchor (the last anchor given and updated).
  FrameIndex addJoint(int j, FrameIndex frame, Eigen::Vector3d& anchor) {
    const mjModel& m = *mj_;
    const std::string joint = name(mjOBJ_JOINT, j, "joint");
    const Eigen::Vector3d position = vectorOf(m.jnt_pos + 3 * j);
    const Eigen::Vector3d axis = vectorOf(m.jnt_axis + 3 * j);
    const int qpos = m.jnt_qposadr[j];
    const int dof = m.jnt_dofadr[j];
    const int type = m.jnt_type[j];
    const double stiffness = passiveStiffness(j);
    if (type == mjJNT_FREE) {
      const char* const translations[] = {"_x", "_y", "_z"};
      for (int i = 0; i < 3; ++i) {
        const std::string slide = added(joint + translations[i]);
        frame = model_.addPrismatic(slide, frame, Eigen::Vector3d::Unit(i));
        start(slide, m.qpos0[qpos + i]);
        if (stiffness != 0.0 || passiveDamping(dof + i) != 0.0)  // its rate is the body's velocity in the ground's axes
          model_.addJointSpringDamper(added(slide + "_spring"), slide, stiffness, passiveDamping(dof + i), m.qpos_spring[qpos + i]);
      }
      return addBall(j, {"_rx", "_ry", "_rz"}, frame, qpos + 3, dof + 3);
    }
    if (position != anchor) frame = model_.addOffset(added(joint + "_anchor"), frame, position - anchor);
    anchor = position;
    if (type == mjJNT_BALL) return addBall(j, {"_x", "_y", "_z"}, frame, qpos, dof);
    frame = type == mjJNT_HINGE ? model_.addRevolute(added(joint), frame, axis)
                                : model_.addPrismatic(added(joint), frame, axis);
    start(joint, 0.0);  // coordinates count from the joint's reference, qpos0
    if (stiffness != 0.0 || passiveDamping(dof) != 0.0)
      model_.addJointSpringDamper(added(joint + "_spring"), joint, stiffness, passiveDamping(dof), m.qpos_spring[qpos] - m.qpos0[qpos]);
    if (m.dof_armature[dof] != 0.0) model_.addArmature(joint, m.dof_armature[dof]);
    return frame;
  }

  /// The start orientation, the quaternion at qpos0 + `quaternion`, as an offset J_start (where it
  /// is not the identity), then a ball joint (Model::addBallJoint) whose rotation vector, from the
  /// start, starts at zero: its chart ends only after a turn of 1.8π from the start. MuJoCo's spring
  /// of the joint, the torque −k log(q_spring⁻¹ q) on its angular velocity, is −k J(φ)ᵀ φ = −k φ on
  /// the rotation vector's rates (Kφ = 0): a joint spring on each component, where the spring's
  /// orientation is the start's (MuJoCo's wraps the logarithm at a half turn; this one does not).
  /// Its damper, −c ω on the same angular velocity (the dofs from `rotation_dof`), is a rotational
  /// damper across the joint.
  FrameIndex addBall(int j, std::array<const char*, 3> suffixes, FrameIndex frame, int quaternion, int rotation_dof) {
    const mjModel& m = *mj_;
    const std::string joint = name(mjOBJ_JOINT, j, "joint");
    const double stiffness = passiveStiffness(j);
    const std::array<double, 3> damping{passiveDamping(rotation_dof), passiveDamping(rotation_dof + 1),
                                        passiveDamping(rotation_dof + 2)};
    const Eigen::Matrix3d start_rotation = rotationOf(m.qpos0 + quaternion);
    if (!start_rotation.isIdentity(1e-15))
      frame = model_.addOffset(added(joint + "_start"), frame, Eigen::Vector3d::Zero(), start_rotation);
    std::array<std::string, 3> names;
    for (std::size_t i = 0; i < 3; ++i) {
      names[i] = added(joint + suffixes[i]);
      start(names[i], 0.0);
    }
    const FrameIndex exit = model_.addBallJoint(names, frame);
    if (stiffness != 0.0) {
      if (!rotationOf(m.qpos_spring + quaternion).isApprox(start_rotation, 1e-12))
        throw std::invalid_argument("joint '" + joint + "': a spring whose orientation is not the start's, which mbsopt does not model");
      for (const std::string& component : names) model_.addJointSpringDamper(added(component + "_spring"), component, stiffness, 0.0);
    }
    if (damping[0] != damping[1] || damping[0] != damping[2])
      throw std::invalid_argument("joint '" + joint + "': unequal dampings of its rotation's dofs, which mbsopt does not model");
    if (damping[0] != 0.0) model_.addRotationalDamper(added(joint + "_damper"), frame, exit, damping[0]);
    return exit;
  }

  /// Joint j's stiffness and dof d's damping, zero where the file's option disables passive forces.
  double passiveStiffness(int j) const { return passive() ? mj_->jnt_stiffness[j] : 0.0; }
  double passiveDamping(int d) const { return passive() ? mj_->dof_damping[d] : 0.0; }
  bool passive() const { return !(mj_->opt.disableflags & mjDSBL_PASSIVE); }

  std::string added(const std::string& name) {
    contents_.names.push_back(name);
    return contents_.names.back();
  }

  void start(const std::string& coordinate, double q0) { contents_.starts.push_back({coordinate, q0, 0.0}); }

  Model& model_;
  std::string path_, text_;
  MujocoModel mj_;
  std::vector<std::string> ignore_;
  std::vector<FrameIndex> frames_;  ///< per MuJoCo body, its B_frame
  ModelFileContents contents_;
};

}  // namespace

const std::vector<std::string>& modelFileFeatures() {
  static const std::vector<std::string> features{"contacts", "limits", "actuators", "tendons", "armature", "friction_loss"};
  return features;
}

ModelFileContents addModelFile(Model& model, const std::string& path, const std::vector<std::string>& ignore) {
  return ModelFileReader(model, path, ignore).read();
}

}  // namespace mbsopt
