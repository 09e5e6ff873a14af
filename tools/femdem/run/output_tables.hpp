// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The one table of a run's outputs: every history.csv column and every summary.json "extra"
// key, with its unit, its meaning and how its value is read from a run. The history header,
// the rows, the summary's extra keys and the tables of docs/OUTPUTS.md all come from here
// (tests/tools/test_output_tables.cpp checks the doc against it). Adding an output is one line
// in output_tables.cpp.
#include <string>
#include <vector>

#include "tools/femdem/run/history_sample.hpp"

namespace femdem {

class RestMonitor;
class PeakMonitor;
class CompactionCurve;

// A column (or key) whose value is read from an S.
template <class S>
struct OutputEntry {
  const char* name;
  const char* unit;  // "-" for a ratio or count
  const char* meaning;
  double (*value)(const S&);
};

// What the run's history columns are for this model.
struct HistoryLayout {
  std::vector<std::string> bodies, walls;
  bool body_contact = false;  // contact.* columns
  bool compaction = false;    // compaction.* columns
};
std::vector<std::string> history_columns(const HistoryLayout& layout);
// The values of one row, in history_columns order (`row` is reused).
void history_row(const HistorySample& s, std::vector<double>& row);

// What summary.json's "extra" keys are read from at the end of a run.
struct RunRecord {
  const Simulation& sim;
  double setup_time_s = 0.0, loop_time_s = 0.0;
  const RestMonitor& rest;
  const PeakMonitor& peaks;
  const CompactionCurve* compaction = nullptr;  // null without [compaction]
};
// summary.json's "extra" object: the keys that apply to this run, with their values.
std::vector<std::pair<std::string, double>> summary_extra(const RunRecord& run);

// The Markdown tables of docs/OUTPUTS.md: history columns (run, per body, per wall, contact,
// compaction) and summary extra keys.
std::string output_tables_markdown();

}  // namespace femdem
