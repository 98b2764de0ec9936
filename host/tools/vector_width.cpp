#include "tools/vector_width.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "util/child_process.h"
#include "util/error.h"
#include "util/temporary_directory.h"

namespace clpt {
namespace {

// A cold compile of the largest kernel takes seconds; this only stops a child that hangs.
constexpr double kProbeTimeoutS = 300;
// How much of a failing child's own message goes into the reason.
constexpr size_t kReasonChars = 200;

constexpr const char* kVectorised = "vectorized loop (vectorization width: ";
constexpr const char* kNotVectorised = "loop not vectorized";
// Reasons (after "loop not vectorized: ") that keep a whole work-item loop scalar; the ones
// tests/vectorised_cli.sh fails on.
constexpr const char* kBlockers[] = {"instruction return type cannot be vectorized",
                                     "call instruction cannot be vectorized", "loop contains a switch statement"};
constexpr const char* kNotBeneficial = "the cost-model indicates that vectorization is not beneficial";
// The inliner's remarks ("'f' inlined into 'g' ...", "'f' not inlined into 'g' ...") name the
// function being compiled; PoCL's work-group functions are named _pocl_kernel_KERNEL_workgroup...
constexpr const char* kInlinedInto = "inlined into '";
constexpr const char* kWorkGroupFunction = "_pocl_kernel_";

// Environment variables the child must not inherit: the probe's own settings (replaced), an
// injected fault (it would fail the probe, not the render), and an MPI launcher's (the child is
// one process, not a rank of the job).
bool inherited(const std::string& entry) {
  const std::string name = entry.substr(0, entry.find('='));
  for (const char* own : {"POCL_VECTORIZER_REMARKS", "POCL_CACHE_DIR", "CLPT_CACHE_DIR", "CLPT_INJECT_FAULT"})
    if (name == own) return false;
  for (const char* launcher : {"OMPI_", "PMIX_", "PMI_"})
    if (name.rfind(launcher, 0) == 0) return false;
  return true;
}

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// What a failed child said about it: its last "clpt: " message (the remarks fill the output
// before it), else the end of its output.
std::string child_message(const std::string& output) {
  std::string message;
  const size_t at = output.rfind("clpt: ");
  if (at != std::string::npos) {
    message = output.substr(at, output.find('\n', at) - at);
  } else {
    message = output.size() > kReasonChars ? output.substr(output.size() - kReasonChars) : output;
  }
  while (!message.empty() && (message.back() == '\n' || message.back() == ' ')) message.pop_back();
  if (message.size() > kReasonChars) message = message.substr(0, kReasonChars) + "...";
  return message;
}

}  // namespace

std::string VectorWidthReport::describe() const {
  if (!known) return "unknown (" + why + ")";
  std::ostringstream o;
  o << lanes << (lanes == 1 ? " work-item" : " work-items") << " (";
  if (!blockers.empty()) {
    o << "work-item loops kept scalar: ";
    for (auto it = blockers.begin(); it != blockers.end(); ++it)
      o << (it == blockers.begin() ? "" : ", ") << it->second << " by " << it->first;
    o << "; ";
  }
  if (loops_by_width.empty()) {
    o << "no loop vectorised";
  } else {
    o << "vectorised loops: ";
    for (auto it = loops_by_width.rbegin(); it != loops_by_width.rend(); ++it)
      o << (it == loops_by_width.rbegin() ? "" : ", ") << it->second << " at " << it->first;
  }
  o << "; " << not_vectorised << " not)";
  return o.str();
}

VectorWidthReport unknown_vector_width(const std::string& why) {
  VectorWidthReport report;
  report.why = why;
  return report;
}

VectorWidthReport parse_vectoriser_remarks(const std::string& text) {
  enum class Kind { Vectorised, Scalar, Blocker, KernelSource, WorkGroupFunction };
  struct Event {
    size_t at;
    Kind kind;
    uint32_t width;
    const char* blocker = nullptr;
  };
  std::vector<Event> events;
  const std::string vectorised = kVectorised;
  for (size_t at = text.find(vectorised); at != std::string::npos; at = text.find(vectorised, at + 1)) {
    size_t end = at + vectorised.size();
    uint32_t width = 0;
    while (end < text.size() && text[end] >= '0' && text[end] <= '9' && width < (1u << 16))
      width = width * 10 + uint32_t(text[end++] - '0');
    // A width that is not a plain number (a scalable "vscale x 4") says nothing of work-items.
    if (width > 0 && end < text.size() && text[end] == ',') events.push_back({at, Kind::Vectorised, width});
  }
  const std::string scalar = kNotVectorised;
  for (size_t at = text.find(scalar); at != std::string::npos; at = text.find(scalar, at + 1))
    if (at + scalar.size() >= text.size() || text[at + scalar.size()] != ':') events.push_back({at, Kind::Scalar, 0});
  const std::string reason_prefix = scalar + ": ";
  for (const char* blocker : kBlockers) {
    const std::string needle = reason_prefix + blocker;
    for (size_t at = text.find(needle); at != std::string::npos; at = text.find(needle, at + 1))
      events.push_back({at, Kind::Blocker, 0, blocker});
  }
  const std::string not_beneficial = kNotBeneficial;
  for (size_t at = text.find(not_beneficial); at != std::string::npos; at = text.find(not_beneficial, at + 1))
    events.push_back({at, Kind::Scalar, 0});
  const std::string inlined = kInlinedInto;
  bool marked = false;
  for (size_t at = text.find(inlined); at != std::string::npos; at = text.find(inlined, at + 1)) {
    const bool work_group = text.compare(at + inlined.size(), std::string(kWorkGroupFunction).size(),
                                         kWorkGroupFunction) == 0;
    marked |= work_group;
    events.push_back({at, work_group ? Kind::WorkGroupFunction : Kind::KernelSource, 0});
  }
  std::sort(events.begin(), events.end(), [](const Event& a, const Event& b) { return a.at < b.at; });

  VectorWidthReport report;
  bool counting = !marked;  // unmarked text: every loop counts
  for (const Event& e : events) {
    if (e.kind == Kind::KernelSource || e.kind == Kind::WorkGroupFunction) {
      if (marked) counting = e.kind == Kind::WorkGroupFunction;
    } else if (counting) {
      if (e.kind == Kind::Vectorised)
        ++report.loops_by_width[e.width];
      else if (e.kind == Kind::Blocker)
        ++report.blockers[e.blocker];
      else
        ++report.not_vectorised;
    }
  }
  if (report.loops_by_width.empty() && report.not_vectorised == 0)
    return unknown_vector_width("the compiler printed no loop-vectoriser remarks");
  report.known = true;
  report.widest = report.loops_by_width.empty() ? 1 : report.loops_by_width.rbegin()->first;
  report.lanes = 1;
  int most = 0;
  if (report.blockers.empty())
    for (const auto& [width, loops] : report.loops_by_width)  // ascending: a tie goes to the wider
      if (loops >= most) most = loops, report.lanes = width;
  return report;
}

bool reports_vector_width(const DeviceInfo& device) {
  return device.is_pocl_cpu();
}

std::vector<std::string> vector_width_probe_arguments(const RenderRequest& request, const DevicePlan& device,
                                                      const std::string& film_path) {
  const RenderSettings& s = request.scene.settings;
  std::vector<std::string> args = {request.scene.file,
                                   "--device", std::to_string(device.device.index),
                                   "--precision", precision_name(request.precision),
                                   "--form", execution_form_name(device.form),
                                   "--megakernel-loop", megakernel_loop_name(request.megakernel_loop),
                                   "--scene-loops", scene_loops_name(request.scene_loops),
                                   "--cpu-vector-bits", cpu_vector_bits_name(request.cpu_vector_bits),
                                   "--sphere-reads", sphere_reads_name(request.sphere_reads)};
  if (request.intersection) args.insert(args.end(), {"--intersection", intersection_name(*request.intersection)});
  if (!s.estimator.empty()) args.insert(args.end(), {"--estimator", s.estimator});
  if (s.rr_from >= 0) args.insert(args.end(), {"--rr-from", std::to_string(s.rr_from)});
  if (request.generic_kernel) args.push_back("--generic");
  if (request.local_size) args.insert(args.end(), {"--local-size", std::to_string(request.local_size)});
  args.insert(args.end(), {"--width", "16", "--height", "8", "--spp", "1", "--sampler", "jitter", "--no-cache",
                           "-q", "-o", film_path});
  return args;
}

VectorWidthReport probe_vector_width(const RenderRequest& request, const DevicePlan& device,
                                     const std::string& clpt_executable) {
  if (!reports_vector_width(device.device)) return unknown_vector_width("the driver does not report it");
  if (clpt_executable.empty()) return unknown_vector_width("the path of this executable cannot be read");
  try {
    const TemporaryDirectory dir("clpt-vector-width");
    std::filesystem::create_directory(dir.file("pocl-cache"));
    std::filesystem::create_directory(dir.file("clpt-cache"));
    std::vector<std::string> argv = {clpt_executable, "render"};
    for (std::string& a : vector_width_probe_arguments(request, device, dir.file("probe.pfm")))
      argv.push_back(std::move(a));
    std::vector<std::string> env;
    for (std::string& entry : current_environment())
      if (inherited(entry)) env.push_back(std::move(entry));
    env.insert(env.end(), {"POCL_VECTORIZER_REMARKS=1", "POCL_CACHE_DIR=" + dir.file("pocl-cache"),
                           "CLPT_CACHE_DIR=" + dir.file("clpt-cache")});
    const std::string output_path = dir.file("remarks.txt");
    const ChildOutcome outcome = run_child_process(argv, env, output_path, kProbeTimeoutS);
    const std::string output = read_text(output_path);
    if (!outcome.succeeded()) {
      const std::string message = child_message(output);
      return unknown_vector_width("the probe render " + outcome.failure + (message.empty() ? "" : ": " + message));
    }
    return parse_vectoriser_remarks(output);
  } catch (const std::exception& e) {  // the temporary directory: no disk space, no permission
    return unknown_vector_width(std::string("the probe could not run: ") + e.what());
  }
}

std::string this_executable() {
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  return ec ? std::string() : exe.string();
}

}  // namespace clpt
