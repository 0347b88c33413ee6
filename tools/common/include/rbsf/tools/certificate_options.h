#pragma once
/// \file
/// \brief The certificate options of every tool that certifies plans (plan-reorientation,
///        rbsf-replay, the controller loop example, the bench programs), parsed in one
///        place into plan::CertificateSettings (rbsf/plan/certificate.h):
///
///   --trials N          a fixed count of closed-loop trials, 1..100000; without it the
///                       certificate is sequential
///   --trial-batch N     sequential: trials between two looks at the bound (default 64)
///   --max-trials N      sequential: the cap on trials (default 512), at least the batch
///   --confidence C      of the lower bound of the success rate, in [0.5, 1) (default 0.95)
///   --required-rate R   certified when that bound is at least R, in [0, 1] (default 0.95)
///
/// A bad value, or --trial-batch / --max-trials with --trials, is an InputError naming the
/// option (exit status 2).

#include <CLI/CLI.hpp>
#include <string>

#include "rbsf/plan/certificate.h"

namespace rbsf::tools {

/// \brief The options as given (empty: not given).
struct CertificateOptions {
  std::string trials, batch, max_trials, confidence, required_rate;

  /// \brief Register the five options on `app`; their help states the defaults of
  ///        plan::CertificateSettings.
  void addTo(CLI::App& app);

  /// \brief Parse the options given into `settings` (the others keep its values).
  /// \throws InputError naming the option.
  void apply(plan::CertificateSettings& settings) const;
};

}  // namespace rbsf::tools
