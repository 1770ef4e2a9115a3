#include "mbsopt/io/element_type.hpp"

namespace mbsopt {

// Each in its own file of 7-io/elements/.
ElementType offsetElement();
ElementType revoluteElement();
ElementType prismaticElement();
ElementType curveSliderElement();
ElementType sphericalElement();
ElementType ballElement();

const std::vector<ElementType>& elementTypes() {
  static const std::vector<ElementType> registry{
      offsetElement(), revoluteElement(), prismaticElement(), curveSliderElement(), sphericalElement(), ballElement(),
  };
  return registry;
}

}  // namespace mbsopt
