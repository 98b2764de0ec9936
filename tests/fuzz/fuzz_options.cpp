// libFuzzer harness for the command-line option parser: the input is split at NUL bytes into
// arguments after "clpt" and parsed by the very app `clpt` uses (cli/app.h), with every
// subcommand's options and checks. No command ever runs (nothing renders or touches a device).
// A CLI11 parse error or --help/--version is the normal outcome for bad input; any other
// exception, a crash or a sanitizer report is a finding. Built with CLPT_FUZZ=ON.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <vector>

#include "cli/app.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::vector<std::string> args = {"clpt"};
  std::string current;
  for (size_t i = 0; i < size; ++i) {
    if (data[i] == 0) {
      args.push_back(current);
      current.clear();
    } else {
      current.push_back(static_cast<char>(data[i]));
    }
  }
  if (!current.empty()) args.push_back(current);
  if (args.size() > 64) return 0;  // argument lists this long tell nothing new
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());

  clpt::ClptApp cli;
  try {
    cli.app.parse(static_cast<int>(argv.size()), argv.data());
    (void)cli.chosen();  // a successful parse must have chosen a command
  } catch (const CLI::Error&) {
    // ParseError (bad option, value, or count) and Success (--help, --version): expected.
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fuzz_options: parse threw %s\n", e.what());
    std::abort();
  }
  return 0;
}
