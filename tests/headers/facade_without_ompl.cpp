// The controller facade's public headers, compiled with the project's include directories
// and Eigen only: a cell controller that links the facade does not need OMPL's or Ipopt's
// headers. The build fails when one of them leaks into the facade's includes.
#include "rbsf/controller/reorientation_controller.h"

namespace {
[[maybe_unused]] rbsf::controller::ReorientationRequest request;
}  // namespace
