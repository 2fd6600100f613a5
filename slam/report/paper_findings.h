// The paper's qualitative findings (`qualitative_findings` in
// configs/paper_results.json) decided by numbers: each finding is matched by
// the start of its text to a rule, and the rule is applied to the measured
// numbers of a built report and, where the paper publishes them, to the
// paper's own (docs/experiments.md, "Agreement with the paper").
#pragma once

#include <string>
#include <vector>

#include "slam/report/report_table.h"
#include "slam/report/session_matrix.h"

namespace duskmap {

enum class FindingVerdict { kReproduced, kNotReproduced, kNotDecided };
const char* FindingVerdictName(FindingVerdict verdict);

struct FindingCheck {
  std::string finding;    // the paper's text
  std::string criterion;  // the numeric rule that decides it ("" when none does)
  FindingVerdict verdict = FindingVerdict::kNotDecided;
  std::string measured;  // the numbers behind the verdict
  // The rule applied to the paper's own numbers: "holds", "does not hold" or
  // why it cannot be (e.g. per-session values not published).
  std::string paper;
};

// One check per finding, in the paper's order; a finding no rule matches is
// not decided. `tables` as BuildReport makes them.
std::vector<FindingCheck> CheckPaperFindings(const std::vector<ReportTable>& tables,
                                             const SingleMapMatrix& single_maps,
                                             const std::vector<std::string>& findings);

}  // namespace duskmap
