// What `clpt tradeoff` writes: the per-run CSV, the JSON report, the stdout tables and the
// gnuplot script of the RMSE-versus-time plot. Text only; files are written by the command.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "tools/tradeoff.h"

namespace clpt {

struct TradeoffReference {
  std::string path;
  int width = 0, height = 0;
  std::optional<uint64_t> spp;  // clpt:spp of the reference, when it has one
  double noise_rms = 0;         // RMS standard error of its pixel means (tools/tradeoff.h)
};

struct TradeoffResult {
  std::string scene;
  uint64_t seed = 0;
  TradeoffReference reference;
  std::vector<Combination> combinations;  // in the order of the command line
  std::vector<TradeoffRun> runs;          // budget runs, then --target-from runs
  std::vector<ErrorTarget> targets;
};

// One CSV field: quoted (with quotes doubled) when it holds a comma, quote, CR or LF (RFC 4180).
std::string csv_field(const std::string& text);

// Header row, then one row per run. Unknown values (noise and bias below 2 spp, budget of a
// fixed-spp run) are empty fields.
std::string tradeoff_csv(const std::vector<TradeoffRun>& runs);

// Everything: reference, runs, targets and the time each combination takes to reach each target.
// Unknown or non-finite numbers are null.
std::string tradeoff_json(const TradeoffResult& result);

// One line describing a finished run, for stdout while the measurement goes on.
std::string run_summary_line(const TradeoffRun& run);

// The "time to reach RMSE" table: one row per combination, one column per target.
std::string time_to_error_table(const TradeoffResult& result);

// A gnuplot script drawing log RMSE against log render time, one curve per combination, the
// targets as grey horizontal lines, into the PNG `png_path` (width x height pixels).
std::string gnuplot_script(const TradeoffResult& result, const std::string& png_path, int width = 900,
                           int height = 600);

}  // namespace clpt
