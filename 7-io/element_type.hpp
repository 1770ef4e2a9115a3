// The kinematic element types of a scene file's `elements:` section, one registry (entry_type.hpp):
// each type's name, what it is, the keys its entry takes besides name, type and parent, and how it
// adds itself to the model. A type is one file of 7-io/elements/ and one line of element_type.cpp's
// table.
#pragma once

#include <string>
#include <vector>

#include "mbsopt/io/entry_type.hpp"

namespace mbsopt {

/// What an element type's reader is given besides what every section's entry has: the frame it
/// starts from, and the starts and names of the coordinates and frames it adds.
class ElementEntry : public SectionEntry {
 public:
  using SectionEntry::initialValues;
  /// The frame the element starts from (its `parent`: the ground or an element placed before).
  virtual FrameIndex parent() const = 0;
  /// The start of the joint coordinate `coordinate`: the entry's `motion` (a driven joint) or its
  /// q0 and v0 (both 0 by default; in deg only where `angular`).
  virtual void motionOrInitialValues(const std::string& coordinate, bool angular) = 0;
  /// The start of the joint coordinate `coordinate` given as numbers (SI units).
  virtual void initialValues(const std::string& coordinate, double q0, double v0) = 0;
  /// A further name the entry adds to the model (an intermediate frame and its coordinate): refused
  /// where another entry of the file has it, and located at this entry in later errors.
  virtual void claimName(const std::string& added) = 0;
};

using ElementType = EntryType<ElementEntry>;

/// offset, revolute, prismatic, curve_slider, spherical.
const std::vector<ElementType>& elementTypes();

}  // namespace mbsopt
