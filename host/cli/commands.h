// Subcommands of the `clpt` command line. Each registers its options on a CLI11 app and runs;
// main.cpp only dispatches and maps clpt::Error to exit codes.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>

namespace clpt {

// Adds the subcommand to `app`; the returned function runs it after parsing (returns exit code).
std::function<int()> add_render_command(CLI::App& app);
std::function<int()> add_devices_command(CLI::App& app);
std::function<int()> add_bench_command(CLI::App& app);
std::function<int()> add_cache_command(CLI::App& app);
std::function<int()> add_scene_transform_command(CLI::App& app);
std::function<int()> add_kernels_command(CLI::App& app);
std::function<int()> add_verify_command(CLI::App& app);
#ifdef CLPT_WITH_OIIO
std::function<int()> add_compare_command(CLI::App& app);
std::function<int()> add_tradeoff_command(CLI::App& app);
#endif

}  // namespace clpt
