// One propagation of the planner: SimPropagator::propagate over one propagation step
// (20 simulator steps of 1 ms) from the default part at rest on the default cell, on the
// planner's own setup (ReorientationPlanner::setup, the 30 degree problem):
//   Held:    the holding tau (phase C, every contact sticking);
//   Sampled: 256 controls drawn by the planner's PhaseControlSampler at the start state,
//            used in turn (the mix of phases the search sees first).
#include <benchmark/benchmark.h>

#include <ompl/control/SpaceInformation.h>
#include <ompl/control/spaces/RealVectorControlSpace.h>
#include <ompl/util/RandomNumbers.h>

#include <string>

#include "rbsf/dynamics/core/holding.h"
#include "rbsf/dynamics/io/cell_file.h"
#include "rbsf/planner/kinodynamic/reorientation_planner.h"

namespace rbsf {
namespace {

namespace oc = ompl::control;

struct PropagationFixture {
  RbsfModel model{loadCell(std::string(RBSF_SOURCE_DIR) + "/cells/default.yaml")};
  planner::ReorientationPlanner planner{model, planner::PlannerSettings{}};
  planner::PlannerSetup setup;
  oc::SpaceInformationPtr si;
  ompl::base::State *start = nullptr, *result = nullptr;
  double step = 0.0;

  PropagationFixture() {
    ompl::RNG::setSeed(1);
    planner::Problem p;
    p.start = {0.1, 0.40, 0.0};
    p.goal = {0.1, 0.40, -30 * M_PI / 180};
    setup = planner.setup(p);
    setup.simple_setup->setup();
    si = setup.simple_setup->getSpaceInformation();
    start = si->allocState();
    result = si->allocState();
    setup.space->fromSim(SimState(setup.q0, VecQ::Zero(setup.q0.size())), start);
    step = si->getPropagationStepSize();
  }
  ~PropagationFixture() {
    si->freeState(start);
    si->freeState(result);
  }
  void set(oc::Control* c, const VecU& tau) const {
    auto* u = c->as<oc::RealVectorControlSpace::ControlType>();
    for (int j = 0; j < tau.size(); ++j) u->values[j] = tau[j];
  }
};

void BM_PropagationHeld(benchmark::State& state) {
  PropagationFixture f;
  ModelData data(f.model.numFingers());
  f.model.updateContacts(f.setup.q0, data);
  const HoldingSolution hold = holdingTorques(f.model, f.setup.q0, data);
  oc::Control* c = f.si->allocControl();
  f.set(c, hold.tau);
  for (auto _ : state) {
    f.setup.propagator->propagate(f.start, c, f.step, f.result);
    benchmark::ClobberMemory();
  }
  f.si->freeControl(c);
}
BENCHMARK(BM_PropagationHeld);

void BM_PropagationSampled(benchmark::State& state) {
  PropagationFixture f;
  const oc::ControlSamplerPtr sampler = f.si->allocControlSampler();
  std::vector<oc::Control*> controls(256);
  for (oc::Control*& c : controls) {
    c = f.si->allocControl();
    sampler->sample(c, f.start);
  }
  std::size_t k = 0;
  for (auto _ : state) {
    f.setup.propagator->propagate(f.start, controls[k], f.step, f.result);
    k = (k + 1) % controls.size();
    benchmark::ClobberMemory();
  }
  for (oc::Control* c : controls) f.si->freeControl(c);
}
BENCHMARK(BM_PropagationSampled);

}  // namespace
}  // namespace rbsf
