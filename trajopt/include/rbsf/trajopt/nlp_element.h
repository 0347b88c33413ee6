#pragma once
/// \file
/// \brief The two kinds of NLP element the optimiser stacks (in the manner of ifopt):
///        constraint sets g_lo <= g(z) <= g_hi with a sparse Jacobian whose structure is
///        fixed once, and cost terms J(z) with a gradient.

#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

#include <utility>

#include <Eigen/Core>

namespace rbsf::trajopt {

/// \brief Read-only view of the whole decision vector z (decision_layout.h).
using ConstVectorRef = Eigen::Ref<const Eigen::VectorXd>;
/// \brief Writable view of a slice of a vector.
using VectorRef = Eigen::Ref<Eigen::VectorXd>;

/// \brief The sparse structure of the Hessian of the Lagrangian (lower triangle, row >= col):
///        elements ask for the slot of each entry they write; repeated entries share one.
class HessianPattern {
 public:
  /// \brief Index into the value array of entry (r, c) (or (c, r)), created when new.
  int slot(int r, int c) {
    if (r < c) std::swap(r, c);
    const std::int64_t key = (static_cast<std::int64_t>(r) << 32) | static_cast<std::uint32_t>(c);
    const auto [it, added] = index_.try_emplace(key, static_cast<int>(rows_.size()));
    if (added) {
      rows_.push_back(r);
      cols_.push_back(c);
    }
    return it->second;
  }
  int size() const { return static_cast<int>(rows_.size()); }
  const std::vector<int>& rows() const { return rows_; }
  const std::vector<int>& cols() const { return cols_; }

 private:
  std::unordered_map<std::int64_t, int> index_;
  std::vector<int> rows_, cols_;
};

/// \brief A block of constraint rows.
class ConstraintSet {
 public:
  virtual ~ConstraintSet() = default;
  /// \brief Name for messages and tests.
  virtual std::string name() const = 0;
  /// \brief Number of rows.
  virtual int rows() const = 0;
  /// \brief Lower and upper bounds of each row (+-1e20 for none, Ipopt's infinity).
  virtual void bounds(VectorRef lower, VectorRef upper) const = 0;
  /// \brief g(z), one entry per row.
  virtual void values(const ConstVectorRef& z, VectorRef g) const = 0;
  /// \brief Structural non-zeros (local row, global column of z), fixed for the solve.
  virtual const std::vector<std::pair<int, int>>& structure() const = 0;
  /// \brief dg/dz at the entries of structure(), in its order.
  virtual void jacobian(const ConstVectorRef& z, double* values) const = 0;
  /// \brief Register the entries of sum_r lambda_r d^2 g_r / dz^2 (none: linear rows).
  virtual void hessianStructure(HessianPattern&) {}
  /// \brief values[slot] += sum_r lambda_r d^2 g_r / dz^2 (lambda: this set's rows).
  virtual void addHessian(const ConstVectorRef&, const double* /*lambda*/,
                          double* /*values*/) const {}
};

/// \brief A term of the objective.
class CostTerm {
 public:
  virtual ~CostTerm() = default;
  virtual std::string name() const = 0;
  /// \brief J(z).
  virtual double value(const ConstVectorRef& z) const = 0;
  /// \brief grad += dJ/dz.
  virtual void addGradient(const ConstVectorRef& z, VectorRef grad) const = 0;
  /// \brief Register the entries of d^2 J / dz^2.
  virtual void hessianStructure(HessianPattern& pattern) = 0;
  /// \brief values[slot] += sigma d^2 J / dz^2.
  virtual void addHessian(const ConstVectorRef& z, double sigma, double* values) const = 0;
};

/// \brief Ipopt's default "infinity" for bounds.
inline constexpr double kInfinity = 1e20;

}  // namespace rbsf::trajopt
