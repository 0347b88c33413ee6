#include "rbsf/dynamics/core/forward_dynamics.h"

#include <Eigen/SVD>

namespace rbsf {

void forwardDynamicsU(const RbsfModel& model, const VecQ& q, const VecQ& v, const VecU& tau,
                      ModelData& data) {
  model.updateContacts(q, data);
  model.velocityProducts(q, v, data);
  model.bias(q, v, data.bias);
  model.freeAcceleration(q, tau, data.bias, data.free_acc);
  data.MinvG1 = data.G1;
  model.applyMassInverse(q, data.MinvG1);
  data.A.noalias() = data.G1.transpose() * data.MinvG1;
  data.p = data.h_n;
  data.p.noalias() += data.G1.transpose() * data.free_acc;
  data.lcp = solveLcp(data.A, data.p, data.fn, data.delta_n);
  data.vdot = data.free_acc;
  data.vdot.noalias() += data.MinvG1 * data.fn;
}

double smallestSingularValueG1(const ModelData& data) {
  if (data.G1.cols() == 0) return 0.0;
  Eigen::JacobiSVD<MatQC> svd(data.G1);
  return svd.singularValues().minCoeff();
}

}  // namespace rbsf
