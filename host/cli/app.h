// The clpt command line as a CLI11 app: every subcommand with its options and checks. main.cpp
// parses argv with it and runs the chosen command; the option-parser fuzzer parses arbitrary
// argument lists with the very same app and never runs a command.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <string>
#include <vector>

namespace clpt {

struct ClptApp {
  CLI::App app{"clpt: an OpenCL path tracer for the scenes of Computer Graphics Gems JP 2015, ch. 1"};
  // (subcommand name, what runs it after a successful parse), in registration order.
  std::vector<std::pair<std::string, std::function<int()>>> commands;

  ClptApp();
  // The chosen command's runner; throws Error(Usage) when none was chosen.
  const std::function<int()>& chosen() const;
};

}  // namespace clpt
