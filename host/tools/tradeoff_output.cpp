#include "tools/tradeoff_output.h"

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <sstream>

namespace clpt {
namespace {

std::string printf_string(const char* format, ...) {
  char buffer[512];
  va_list args;
  va_start(args, format);
  std::vsnprintf(buffer, sizeof buffer, format, args);
  va_end(args);
  return buffer;
}

// Shortest round-trip-ish text of a number for CSV; "" when unknown or not finite.
std::string csv_number(double value, bool known = true) {
  return known && std::isfinite(value) ? printf_string("%.9g", value) : "";
}

nlohmann::json json_number(double value, bool known = true) {
  return known && std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

// gnuplot single-quoted string: the only escape is '' for a quote.
std::string gnuplot_string(const std::string& text) {
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("''") : std::string(1, c);
  return out + "'";
}

const char* reach_name(Reach reach) {
  switch (reach) {
    case Reach::Interpolated: return "interpolated";
    case Reach::AtOrBeforeFirst: return "at_or_before_smallest_budget";
    default: return "not_reached";
  }
}

std::string format_reach(const TimeToError& t) {
  switch (t.reach) {
    case Reach::Interpolated: return printf_string("%.3g s", t.seconds);
    case Reach::AtOrBeforeFirst: return printf_string("<= %.3g s", t.seconds);
    default: return "not reached";
  }
}

nlohmann::json run_json(const TradeoffRun& run) {
  const ErrorSplit& e = run.error;
  const bool known = run.noise_known();
  return {
      {"combination", run.combination.label()},
      {"precision", precision_name(run.combination.precision)},
      {"estimator", estimator_name(run.combination.estimator)},
      {"form", execution_form_name(run.combination.form)},
      {"sampler", run.combination.sampler.empty() ? nlohmann::json(nullptr) : nlohmann::json(run.combination.sampler)},
      {"adaptive", run.combination.adaptive},
      {"device", run.combination.device_name},
      {"device_index", run.combination.device_index},
      {"budget_s", json_number(run.budget_s, run.budget_s > 0)},
      {"fixed_spp", run.fixed_spp > 0 ? nlohmann::json(run.fixed_spp) : nlohmann::json(nullptr)},
      {"render_s", json_number(run.render_s)},
      {"build_s", json_number(run.build_s)},
      {"spp", run.spp},
      {"paths", run.paths},
      {"paths_per_s", json_number(run.paths_per_s())},
      {"rmse", json_number(e.rmse)},
      {"relative_mse", json_number(e.relative_mse)},
      {"mse", json_number(e.mse)},
      {"noise_render", json_number(e.noise_render, known)},
      {"noise_reference", json_number(e.noise_reference)},
      {"noise", json_number(e.noise, known)},
      {"bias_sq", json_number(e.bias_sq, known)},
      {"bias_sq_stderr", json_number(e.bias_sq_stderr, known)},
      {"bias_rms", json_number(e.bias_rms, known)},
      {"dropped_samples", run.dropped},
  };
}

// Range of every RMSE plotted and of the targets, widened a little: the target lines must
// lie inside the plot even when no curve reaches them.
std::pair<double, double> rmse_range(const TradeoffResult& result) {
  double lo = HUGE_VAL, hi = 0;
  auto take = [&](double v) {
    if (std::isfinite(v) && v > 0) lo = std::min(lo, v), hi = std::max(hi, v);
  };
  for (const TradeoffRun& run : result.runs) take(run.error.rmse);
  for (const ErrorTarget& t : result.targets) take(t.rmse);
  return {lo / 1.25, hi * 1.25};
}

// Explicit tics for a log axis over [lo, hi]: gnuplot's own are one per decade, which leaves a
// plot of less than a decade with one labelled tic or none. 1-2-5 per decade, finer on short ranges.
std::string log_tics(double lo, double hi) {
  const std::vector<double> mantissas =
      hi / lo >= 10 ? std::vector<double>{1, 2, 5} : std::vector<double>{1, 1.5, 2, 3, 5, 7};
  std::string list;
  for (int exponent = int(std::floor(std::log10(lo))); exponent <= int(std::ceil(std::log10(hi))); ++exponent)
    for (double m : mantissas) {
      const double v = m * std::pow(10.0, exponent);
      if (v >= lo && v <= hi) list += (list.empty() ? "" : ", ") + printf_string("%g", v);
    }
  return "(" + list + ")";
}

// Range of the measured render times, widened like rmse_range.
std::pair<double, double> time_range(const TradeoffResult& result) {
  double lo = HUGE_VAL, hi = 0;
  for (const TradeoffRun& run : result.runs)
    if (std::isfinite(run.render_s) && run.render_s > 0) lo = std::min(lo, run.render_s), hi = std::max(hi, run.render_s);
  return {lo / 1.25, hi * 1.25};
}

}  // namespace

std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

std::string tradeoff_csv(const std::vector<TradeoffRun>& runs) {
  std::ostringstream out;
  out << "run,combination,precision,estimator,form,device,budget_s,render_s,build_s,spp,paths,paths_per_s,"
         "rmse,relative_mse,mse,noise_render,noise_reference,noise,bias_sq,bias_sq_stderr,bias_rms,"
         "dropped_samples\n";
  for (const TradeoffRun& run : runs) {
    const ErrorSplit& e = run.error;
    const bool known = run.noise_known();
    const std::vector<std::string> fields = {
        run.budget_s > 0 ? "budget" : "fixed_spp",
        run.combination.label(),
        precision_name(run.combination.precision),
        estimator_name(run.combination.estimator),
        execution_form_name(run.combination.form),
        run.combination.device_name,
        csv_number(run.budget_s, run.budget_s > 0),
        csv_number(run.render_s),
        csv_number(run.build_s),
        std::to_string(run.spp),
        std::to_string(run.paths),
        csv_number(run.paths_per_s()),
        csv_number(e.rmse),
        csv_number(e.relative_mse),
        csv_number(e.mse),
        csv_number(e.noise_render, known),
        csv_number(e.noise_reference),
        csv_number(e.noise, known),
        csv_number(e.bias_sq, known),
        csv_number(e.bias_sq_stderr, known),
        csv_number(e.bias_rms, known),
        std::to_string(run.dropped),
    };
    for (size_t i = 0; i < fields.size(); ++i) out << (i ? "," : "") << csv_field(fields[i]);
    out << "\n";
  }
  return out.str();
}

std::string tradeoff_json(const TradeoffResult& result) {
  nlohmann::json j;
  j["scene"] = result.scene;
  j["seed"] = result.seed;
  j["reference"] = {{"path", result.reference.path},
                    {"width", result.reference.width},
                    {"height", result.reference.height},
                    {"spp", result.reference.spp ? nlohmann::json(*result.reference.spp) : nlohmann::json(nullptr)},
                    {"noise_rms", json_number(result.reference.noise_rms)}};
  j["definitions"] = {
      {"rmse", "sqrt(mean over pixels and channels of (x - ref)^2)"},
      {"relative_mse", "mean over pixels and channels of (x - ref)^2 / (ref^2 + 1e-2)"},
      {"noise", "mean over pixels and channels of the render's and the reference's variance of the pixel mean"},
      {"bias_sq", "max(0, mse - noise); bias_sq_stderr is the standard error of mse - noise"},
      {"render_s", "measured time of the render passes, kernel build excluded"},
  };
  j["runs"] = nlohmann::json::array();
  for (const TradeoffRun& run : result.runs) j["runs"].push_back(run_json(run));
  j["targets"] = nlohmann::json::array();
  for (const ErrorTarget& target : result.targets) {
    nlohmann::json times = nlohmann::json::array();
    for (const Combination& c : result.combinations) {
      const TimeToError t = time_to_reach(curve_of(result.runs, c.label()), target.rmse);
      times.push_back({{"combination", c.label()},
                       {"status", reach_name(t.reach)},
                       {"seconds", json_number(t.seconds, t.reach != Reach::NotReached)}});
    }
    j["targets"].push_back({{"rmse", json_number(target.rmse)}, {"source", target.source}, {"time_to_reach", times}});
  }
  j["combinations"] = nlohmann::json::array();
  for (const Combination& c : result.combinations)
    j["combinations"].push_back({{"label", c.label()}, {"dominated_by", dominated_by(result.runs, c.label())}});
  return j.dump(2) + "\n";
}

std::string run_summary_line(const TradeoffRun& run) {
  const ErrorSplit& e = run.error;
  std::string line = printf_string("%-30s ", run.combination.label().c_str());
  line += run.budget_s > 0 ? printf_string("budget %-6.3g s:", run.budget_s)
                           : printf_string("%llu spp:", (unsigned long long)run.fixed_spp);
  line += printf_string(" %.3f s, %llu spp, %.3g M paths/s, RMSE %.4g", run.render_s, (unsigned long long)run.spp,
                        run.paths_per_s() * 1e-6, e.rmse);
  if (!run.noise_known()) return line + " (noise and bias unknown below 2 spp)\n";
  return line + printf_string(", noise RMS %.4g, bias RMS %.4g (bias^2 %.3g +- %.2g)\n", std::sqrt(e.noise),
                              e.bias_rms, e.bias_sq, e.bias_sq_stderr);
}

std::string time_to_error_table(const TradeoffResult& result) {
  std::ostringstream out;
  out << "time to reach an RMSE (measured render time, log-log interpolation between budgets):\n";
  for (size_t t = 0; t < result.targets.size(); ++t)
    out << printf_string("  T%zu = RMSE %.4g: %s\n", t + 1, result.targets[t].rmse, result.targets[t].source.c_str());
  size_t width = std::string("combination").size();
  for (const Combination& c : result.combinations) width = std::max(width, c.label().size());
  out << printf_string("%-*s", int(width), "combination");
  for (size_t t = 0; t < result.targets.size(); ++t) out << printf_string("  %-13s", ("T" + std::to_string(t + 1)).c_str());
  out << "\n";
  for (const Combination& c : result.combinations) {
    out << printf_string("%-*s", int(width), c.label().c_str());
    const std::vector<CurvePoint> curve = curve_of(result.runs, c.label());
    for (const ErrorTarget& target : result.targets)
      out << printf_string("  %-13s", format_reach(time_to_reach(curve, target.rmse)).c_str());
    out << "\n";
  }
  std::string dominated;
  for (const Combination& c : result.combinations) {
    const std::vector<std::string> by = dominated_by(result.runs, c.label());
    if (by.empty()) continue;
    dominated += "  " + c.label() + ": dominated by ";
    for (size_t i = 0; i < by.size(); ++i) dominated += (i ? ", " : "") + by[i];
    dominated += "\n";
  }
  out << (dominated.empty() ? std::string("no combination is beaten by another in both time and error\n")
                            : "beaten in both time and error (lower RMSE at every common budget, no longer):\n" +
                                  dominated);
  return out.str();
}

std::string gnuplot_script(const TradeoffResult& result, const std::string& png_path, int width, int height) {
  std::ostringstream s;
  s << "set terminal png size " << width << "," << height << " noenhanced\n";
  s << "set output " << gnuplot_string(png_path) << "\n";
  s << "set logscale xy\nset grid\nset key top right\n";
  s << "set xlabel 'render time (s), kernel build excluded'\n";
  s << "set ylabel " << gnuplot_string("RMSE against " + result.reference.path) << "\n";
  s << "set title " << gnuplot_string("clpt tradeoff: " + result.scene + " (" + std::to_string(result.reference.width) +
                                     "x" + std::to_string(result.reference.height) + ")")
    << "\n";
  // One data block per curve ($c<i>: budget runs) and per fixed-spp point ($f<i>).
  std::vector<std::string> plots;
  for (size_t i = 0; i < result.combinations.size(); ++i) {
    std::ostringstream block;
    for (const CurvePoint& p : curve_of(result.runs, result.combinations[i].label()))
      if (p.seconds > 0 && p.rmse > 0 && std::isfinite(p.seconds) && std::isfinite(p.rmse))
        block << printf_string("%.9g %.9g\n", p.seconds, p.rmse);
    if (block.str().empty()) continue;
    s << "$c" << i << " << EOD\n" << block.str() << "EOD\n";
    // A dominated combination (dominated_by) is drawn dashed and says so.
    const bool dominated = !dominated_by(result.runs, result.combinations[i].label()).empty();
    plots.push_back("$c" + std::to_string(i) + " using 1:2 with linespoints lw 2 pt 7" +
                    (dominated ? " dt 2" : "") + " title " +
                    gnuplot_string(result.combinations[i].label() + (dominated ? " (dominated)" : "")));
  }
  for (size_t i = 0; i < result.runs.size(); ++i) {
    const TradeoffRun& run = result.runs[i];
    if (run.budget_s > 0 || !(run.render_s > 0) || !(run.error.rmse > 0) || !std::isfinite(run.error.rmse)) continue;
    s << "$f" << i << " << EOD\n" << printf_string("%.9g %.9g\n", run.render_s, run.error.rmse) << "EOD\n";
    plots.push_back("$f" + std::to_string(i) + " using 1:2 with points pt 6 ps 2 title " +
                    gnuplot_string(run.combination.label() + " at " + std::to_string(run.fixed_spp) + " spp"));
  }
  if (plots.empty()) {  // nothing measured: an empty, labelled frame rather than a gnuplot error
    s << "set xrange [0.1:10]\nset yrange [0.1:10]\nset label 'no runs to plot' at graph 0.5, 0.5 center\n";
    s << "plot 1 notitle lc rgb 'white'\n";
    return s.str();
  }
  const auto [lo, hi] = rmse_range(result);
  const auto [t_lo, t_hi] = time_range(result);
  s << printf_string("set yrange [%.9g:%.9g]\nset xrange [%.9g:%.9g]\n", lo, hi, t_lo, t_hi);
  s << "set ytics " << log_tics(lo, hi) << "\nset xtics " << log_tics(t_lo, t_hi) << "\n";
  for (size_t t = 0; t < result.targets.size(); ++t) {
    const double e = result.targets[t].rmse;
    if (!(e > 0) || !std::isfinite(e)) continue;
    s << printf_string("set arrow from graph 0, first %.9g to graph 1, first %.9g nohead lw 1 lc rgb 'gray50'\n",
                       e, e);
    s << printf_string("set label 'T%zu' at graph 0.01, first %.9g offset 0, 0.6\n", t + 1, e);
  }
  s << "plot ";
  for (size_t i = 0; i < plots.size(); ++i) s << (i ? ", \\\n     " : "") << plots[i];
  s << "\n";
  return s.str();
}

}  // namespace clpt
