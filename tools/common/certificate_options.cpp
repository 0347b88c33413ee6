#include "rbsf/tools/certificate_options.h"

#include "rbsf/dynamics/core/errors.h"
#include "rbsf/tools/cli_values.h"

namespace rbsf::tools {

void CertificateOptions::addTo(CLI::App& app) {
  const plan::CertificateSettings d;
  app.add_option("--trials", trials,
                 "a fixed number of closed-loop trials of the certificate, 1..100000 (default: "
                 "sequential, batches of --trial-batch until the bound decides or --max-trials; "
                 "fewer than 59 trials cannot certify 0.95 at 95 % confidence)");
  app.add_option("--trial-batch", batch,
                 "sequential certificate: trials between two looks at the bound, 1..100000 "
                 "(default " +
                     std::to_string(d.batch) + ")");
  app.add_option("--max-trials", max_trials,
                 "sequential certificate: the cap on trials, from the batch to 100000 (default " +
                     std::to_string(d.max_trials) + ")");
  app.add_option("--confidence", confidence,
                 "confidence of the lower bound of the success rate, in [0.5, 1) (default " +
                     numberText(d.confidence) + ")");
  app.add_option("--required-rate", required_rate,
                 "certified when the lower bound of the success rate is at least this, in "
                 "[0, 1] (default " +
                     numberText(d.required_rate) + ")");
}

void CertificateOptions::apply(plan::CertificateSettings& s) const {
  if (!trials.empty()) {
    s.trials = static_cast<int>(parseInteger(trials, "--trials", 1, 100000));
    if (!batch.empty())
      throw InputError("--trial-batch: only for a sequential certificate, not with --trials");
    if (!max_trials.empty())
      throw InputError("--max-trials: only for a sequential certificate, not with --trials");
  }
  if (!batch.empty()) s.batch = static_cast<int>(parseInteger(batch, "--trial-batch", 1, 100000));
  if (!max_trials.empty()) {
    s.max_trials = static_cast<int>(parseInteger(max_trials, "--max-trials", 1, 100000));
    if (s.max_trials < s.batch)
      throw InputError("--max-trials: must be at least the batch, " + std::to_string(s.batch) +
                       " (got " + max_trials + ")");
  } else if (s.batch > s.max_trials) {
    throw InputError("--trial-batch: must be at most the cap, " + std::to_string(s.max_trials) +
                     " (got " + batch + ")");
  }
  if (!confidence.empty()) {
    s.confidence = parseNumber(confidence, "--confidence");
    if (!(s.confidence >= 0.5 && s.confidence < 1.0))
      throw InputError("--confidence: must be in [0.5, 1) (got " + confidence + ")");
  }
  if (!required_rate.empty()) {
    s.required_rate = parseNumber(required_rate, "--required-rate");
    if (!(s.required_rate >= 0.0 && s.required_rate <= 1.0))
      throw InputError("--required-rate: must be in [0, 1] (got " + required_rate + ")");
  }
}

}  // namespace rbsf::tools
