// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The compaction curve of a run with [compaction]: the history rows' compaction samples, kept
// for summary.json's "compaction" object (extremes, and the Heckel and Kawakita fits over the
// loading part of the curve; docs/OUTPUTS.md).
#include <vector>

#include "engine/compaction.hpp"
#include "engine/state_archive.hpp"
#include "io/results/summary_writer.hpp"

namespace femdem {

class CompactionCurve {
 public:
  // `expected_rows`: a hint for the reservation (end_time / history_interval).
  CompactionCurve(const CompactionMonitor& monitor, double expected_rows);
  void observe(const CompactionSample& s) { curve_.push_back(s); }
  CompactionSummary summarise() const;
  // wall time spent sampling the compaction columns (docs/PERFORMANCE.md)
  double sample_time_s = 0.0;

  void exchange_state(StateArchive& a) {
    const StateArchive::Scope scope(a, "compaction_curve");
    a.array("samples", curve_, StateArchive::Length::variable);
    a.value("sample_time_s", sample_time_s);
  }

 private:
  const CompactionMonitor& monitor_;
  std::vector<CompactionSample> curve_;
};

}  // namespace femdem
