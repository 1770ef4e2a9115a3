// A mechanism from a model file of the field's standard formats, MJCF (.xml) or URDF (.urdf),
// compiled by MuJoCo's own compiler (its defaults, `fromto` geoms and inertias computed from geoms
// included) and added to a Model as kinetostatic elements and bodies (docs/model-files.md).
//
// Each MuJoCo body B becomes an offset B_placement (its `pos` and `quat` in the parent body), then its
// joints in the order MuJoCo applies them, each about its anchor, then an offset B_frame back from
// the last anchor: B_frame is the body's frame, the body B (its mass and inertia) hangs on it. A hinge
// J is a revolute J, a slide a prismatic J (offsets J_anchor carry the anchors), a ball a ball joint
// J_x, J_y, J_z (Model::addBallJoint), a free joint three prismatics J_x, J_y, J_z along the ground's
// axes and a ball joint J_rx, J_ry, J_rz; both balls are rotation vectors from the start orientation
// (an offset J_start), whose chart ends after a turn of 1.8π from it. A hinge's or slide's coordinate
// is measured from the joint's reference (MuJoCo's qpos0). Joint stiffness and damping become the
// joint spring-damper J_spring (rest at the joint's springref); a ball's stiffness a spring on each
// component of its rotation vector (J_x_spring, …) and its damping the rotational damper J_damper
// across it; a hinge's or slide's armature the rotor inertia J.armature. What the file holds beyond
// that (contacts, limits, actuators, tendons, a free or ball joint's armature, friction loss) is
// refused at its line unless the caller leaves it out by name.
#pragma once

#include <string>
#include <vector>

#include "mbsopt/model/model.hpp"

namespace mbsopt {

/// What a model file may hold that mbsopt does not model, by the name `ignore:` takes.
const std::vector<std::string>& modelFileFeatures();

/// What addModelFile added beside the elements and bodies.
struct ModelFileContents {
  struct Start {
    std::string coordinate;
    double q0, v0;  ///< 0 and 0 but a free joint's position, from the file's qpos0: at rest where the file places it
  };
  std::vector<Start> starts;
  std::vector<std::string> names;     ///< every name added to the model (frames, coordinates, bodies, forces)
  std::vector<std::string> left_out;  ///< one line per feature the file has and `ignore` left out
};

/// Adds the file's mechanism to `model` after its ground (gravity included). Throws SceneError
/// naming the file and the line of the element it cannot take (MuJoCo's compiler errors keep its
/// line); `ignore` names features of modelFileFeatures() to leave out instead.
ModelFileContents addModelFile(Model& model, const std::string& path, const std::vector<std::string>& ignore);

}  // namespace mbsopt
