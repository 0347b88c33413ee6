// The optimiser's least-norm rows (internal_force_constraint.h) against the model and the
// simulator: the squeeze they exclude is felt by no coordinate (G1 and T of RbsfModel), and
// the forces the simulator gives three sticking tips have none of it.
#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "rbsf/dynamics/core/contact_balance.h"
#include "rbsf/dynamics/core/placement.h"
#include "rbsf/dynamics/core/simulator.h"
#include "rbsf/trajopt/internal_force_constraint.h"
#include "trajopt_support.h"

namespace rbsf::trajopt {
namespace {

struct Rest {
  VecQ q;
  double phi, theta;
};

// The default part resting on all three tips at a few poses and base angles.
std::vector<Rest> restingStates(const RbsfModel& model) {
  std::vector<Rest> out;
  for (const auto& [x, phi, theta] : std::array<std::array<double, 3>, 4>{
           {{0.1, 0.0, 0.0}, {0.05, 0.2, 0.1}, {0.12, -0.3, -0.2}, {0.0, 0.5, 0.3}}}) {
    const VecQ q = restingConfiguration(model, Pose{x, 0.40, phi}, theta);
    out.push_back({q, phi, theta});
  }
  return out;
}

// The local vector of internalForceResidual for fingers 0, 1, 2 with the given forces.
std::array<double, 14> local(const Rest& r, const ModelData& data, const VecC& fn, const VecC& ft) {
  std::array<double, 14> x{};
  x[0] = r.phi;
  x[1] = r.theta;
  for (int p = 0; p < 3; ++p) {
    x[2 + p] = r.q[layout::stroke(p)];
    x[5 + p] = fn[p];
    x[8 + p] = ft[p];
    x[11 + p] = data.contacts[p].xi;
  }
  return x;
}

TEST(TrajoptInternalForce, TheSqueezeOfThreeStickingTipsIsFeltByNoCoordinate) {
  const RbsfModel& model = test::defaultModel();
  const double weight = model.cell().object.mass * model.cell().gravity;
  ModelData data(3);
  for (const Rest& r : restingStates(model)) {
    model.updateContacts(r.q, data);
    const Vec2 b(std::cos(r.theta), std::sin(r.theta));
    const double l[3] = {r.q[layout::stroke(0)], r.q[layout::stroke(1)], r.q[layout::stroke(2)]};
    const double h[3] = {l[1] - l[2], l[2] - l[0], l[0] - l[1]};
    VecC fn(3), ft(3);
    for (int i = 0; i < 3; ++i) {  // world force h_i b, in the contact's frame
      fn[i] = 1000.0 * h[i] * b.dot(data.contacts[i].normal);
      ft[i] = 1000.0 * h[i] * b.dot(data.contacts[i].tangent);
    }
    const VecQ felt = data.G1.leftCols(3) * fn + data.T.leftCols(3) * ft;
    EXPECT_LT(felt.norm(), 1e-9 * (fn.norm() + ft.norm())) << felt.transpose();
    // The row sees it: g = sum h_i (1000 h_i) / (m_o g0).
    const auto x = local(r, data, fn, ft);
    const double expected = 1000.0 * (h[0] * h[0] + h[1] * h[1] + h[2] * h[2]) / weight;
    EXPECT_NEAR(internalForceResidual<double>(model, x.data()), expected, 1e-9 * expected);
  }
}

TEST(TrajoptInternalForce, TheSimulatorGivesThreeStickingTipsNoSqueeze) {
  // The default part on three tips needs a friction use of about 0.9 to stick on all
  // three, more than the default cell's tips give at rest: the cell with mu_s 2.
  Cell cell = test::defaultModel().cell();
  cell.friction.mu_static = 2.0;
  const RbsfModel model(cell);
  const Simulator sim(model);
  const ContactBalancer balancer(model);
  ModelData data(3);
  for (const Rest& r : restingStates(model)) {
    const ContactBalance hold = balancer.statics(r.q, ContactSet{0b111u, 0b111u}, data);
    ASSERT_TRUE(hold.solvable);
    SimState state(r.q, VecQ::Zero(r.q.size()));
    SimulatorWorkspace ws(3);
    StepReport report;
    sim.step(state, hold.tau, ws, &report);
    VecC fn(3), ft(3);
    for (int i = 0; i < 3; ++i) {
      ASSERT_EQ(report.contacts[i].mode, ContactMode::kStick) << "finger " << i + 1;
      fn[i] = report.contacts[i].f_n;
      ft[i] = report.contacts[i].f_t;
    }
    model.updateContacts(r.q, data);
    const auto x = local(r, data, fn, ft);
    // The squeeze the forces carry [N]: their component along the unit null vector h / |h|
    // (the row is h . (f . b) / (m_o g0)); least norm leaves none of it.
    const double l[3] = {r.q[layout::stroke(0)], r.q[layout::stroke(1)], r.q[layout::stroke(2)]};
    const double h = std::hypot(l[1] - l[2], l[2] - l[0], l[0] - l[1]);
    const double weight = model.cell().object.mass * model.cell().gravity;
    const double squeeze = internalForceResidual<double>(model, x.data()) * weight / h;
    EXPECT_LT(std::abs(squeeze), 0.01) << "forces " << fn.transpose() << " | " << ft.transpose();
  }
}

}  // namespace
}  // namespace rbsf::trajopt
