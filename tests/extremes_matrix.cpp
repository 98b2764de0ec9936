// The preset x extreme matrix of README "Numerical extremes": renders every extreme scene
// (extreme_scenes.h) in each precision preset, prints a markdown table (pass/fail, worst relative
// error, the model's estimate) and writes it to --out. Exit 1 when a row fails that the safe-range
// model (host/scene/precision_range.h) calls safe and that is not a documented known issue, or
// when a known issue unexpectedly passes (the table and the expectations must then be updated).
//   clpt_extremes_matrix [--presets fast,robust,double] [--only SUBSTRING] [--out FILE]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "extreme_check.h"
#include "scene/precision_range.h"

using namespace clpt;
using namespace clpt::test;

namespace {

std::vector<Precision> parse_presets(const std::string& list) {
  std::vector<Precision> out;
  std::stringstream s(list);
  for (std::string name; std::getline(s, name, ',');) {
    const auto p = parse_precision(name);
    if (!p) throw std::runtime_error("--presets: unknown preset '" + name + "'");
    out.push_back(*p);
  }
  return out;
}

std::string short_number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1e", v);
  return buf;
}

// Until main's kernels implement a preset (or the nee estimator), its build options equal
// robust's (book's) and it renders exactly like robust: its expectations are then robust's.
bool kernels_implement(Precision p) {
  KernelFeatures f;
  f.precision = p;
  KernelFeatures robust = f;
  robust.precision = Precision::Robust;
  return p == Precision::Robust || kernel_build_options(f) != kernel_build_options(robust);
}

bool kernels_implement_nee() {
  KernelFeatures nee, book;
  nee.estimator = Estimator::Nee;
  return kernel_build_options(nee) != kernel_build_options(book);
}

// The model's worst estimate over the scene's spheres and meshes' triangles.
double worst_estimate(const Scene& scene, Precision p) {
  double worst = worst_sphere_precision(scene, p).relative_error;
  for (const TrianglePrecision& t : estimate_mesh_precision(scene, p)) worst = std::max(worst, t.relative_error);
  return worst;
}

// Why a result is or is not as expected.
enum class Expectation { MustPass, KnownIssue, OutOfRange, NeedsNee };

Expectation expectation_for(const Extreme& e, Precision p) {
  if (e.needs_nee && !kernels_implement_nee()) return Expectation::NeedsNee;
  if (!e.known_issue.empty()) return Expectation::KnownIssue;
  const Precision model = kernels_implement(p) ? p : Precision::Robust;
  return precision_range_warnings(e.scene, model).empty() ? Expectation::MustPass : Expectation::OutOfRange;
}

}  // namespace

int main(int argc, char** argv) {
  std::string presets = "fast,robust,double", only, out_path;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (i + 1 < argc && a == "--presets") presets = argv[++i];
    else if (i + 1 < argc && a == "--only") only = argv[++i];
    else if (i + 1 < argc && a == "--out") out_path = argv[++i];
    else {
      std::cerr << "usage: clpt_extremes_matrix [--presets fast,robust,double] [--only SUBSTRING] [--out FILE]\n";
      return 2;
    }
  }
  try {
    const std::vector<Precision> precisions = parse_presets(presets);
    std::vector<Extreme> extremes;
    for (Extreme& e : all_extremes())
      if (only.empty() || e.name.find(only) != std::string::npos) extremes.push_back(std::move(e));
    int family = 0;
    for (const Extreme& e : extremes) family += comparisons_of(e);

    // results[extreme][preset]
    std::vector<std::vector<std::string>> cells(extremes.size());
    std::vector<std::string> notes;
    bool unexpected = false;
    for (Precision p : precisions) {
      ExtremeRun run;
      run.precision = p;
      run.family_comparisons = family;
      for (size_t i = 0; i < extremes.size(); ++i) {
        const Extreme& e = extremes[i];
        const Expectation x = expectation_for(e, p);
        if (x == Expectation::NeedsNee) {
          cells[i].push_back("not run (no nee kernels yet)");
          continue;
        }
        const auto t0 = std::chrono::steady_clock::now();
        const ExtremeResult r = check_extreme(e, run);
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        std::string cell = (r.pass ? "pass " : "**FAIL** ") + short_number(r.worst_relative_error);
        if (x == Expectation::KnownIssue) cell += r.pass ? " (known issue fixed?)" : " (known issue)";
        if (x == Expectation::OutOfRange) cell += " (out of range)";
        const bool bad = (x == Expectation::MustPass && !r.pass) || (x == Expectation::KnownIssue && r.pass);
        unexpected = unexpected || bad;
        cells[i].push_back(cell);
        std::fprintf(stderr, "%-8s %-48s %s  [%s; %.1f s]%s\n", precision_name(p), e.name.c_str(), cell.c_str(),
                     r.detail.c_str(), seconds, bad ? "  UNEXPECTED" : "");
      }
    }

    std::ostringstream table;
    table << "| extreme | estimated error (fast / robust / double) |";
    for (Precision p : precisions) table << " " << precision_name(p) << " |";
    table << "\n|---|---|";
    for (size_t k = 0; k < precisions.size(); ++k) table << "---|";
    table << "\n";
    for (size_t i = 0; i < extremes.size(); ++i) {
      const Extreme& e = extremes[i];
      table << "| " << e.name << " | "
            << short_number(worst_estimate(e.scene, Precision::Fast)) << " / "
            << short_number(worst_estimate(e.scene, Precision::Robust)) << " / "
            << short_number(worst_estimate(e.scene, Precision::Double)) << " |";
      for (const std::string& c : cells[i]) table << " " << c << " |";
      table << "\n";
      if (!e.known_issue.empty()) notes.push_back(e.name + ": " + e.known_issue);
    }
    for (Precision p : precisions)
      if (!kernels_implement(p))
        table << "\n" << precision_name(p) << ": the kernels do not implement this preset yet (its build "
              << "options equal robust's): it rendered like robust and was held to robust's range.\n";
    table << "\nCells: pass/FAIL and the worst relative error of the compared region means or exact "
             "pixels; (out of range): beyond the proven range of the safe-range model, so no "
             "expectation.\n";
    for (const std::string& n : notes) table << "\nKnown issue, " << n << "\n";
    std::cout << table.str();
    if (!out_path.empty()) {
      std::ofstream f(out_path);
      f << table.str();
      if (!f) throw std::runtime_error("--out " + out_path + ": cannot write");
    }
    if (unexpected) std::fprintf(stderr, "clpt_extremes_matrix: results differ from the expectations (UNEXPECTED above)\n");
    return unexpected ? 1 : 0;
  } catch (const std::exception& ex) {
    std::fprintf(stderr, "clpt_extremes_matrix: %s\n", ex.what());
    return 2;
  }
}
