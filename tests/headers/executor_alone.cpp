// The executor's public header, compiled with the include directories of dynamics, plan and
// the executor only: a cell that executes plan files does not need the planner's or the
// optimiser's headers (nor OMPL's or Ipopt's). The build fails when one of them leaks in.
#include "rbsf/executor/plan_runner.h"

namespace {
[[maybe_unused]] rbsf::executor::LoadOptions options;
}  // namespace
