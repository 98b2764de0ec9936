// Running another program as a child process and waiting for it: no shell and no PATH search,
// so arguments reach it exactly as given. Used where clpt measures something only a fresh process
// can show (tools/vector_width.h: a driver that reads its settings from the environment once).
#pragma once

#include <string>
#include <vector>

namespace clpt {

struct ChildOutcome {
  // "" when the child exited with status 0; otherwise one sentence saying why not: it could not
  // be started, exited with status N, was killed by signal N, or ran past its time limit.
  std::string failure;
  bool succeeded() const { return failure.empty(); }
};

// Runs `argv` (argv[0]: the program's path) with exactly the environment `env` ("NAME=value"
// entries), stdin on /dev/null, stdout and stderr both into the file `output_path` (created or
// truncated). Waits for it; after `timeout_s` seconds the child is killed (SIGKILL). Never throws
// for the child's own failures: they are in the outcome.
ChildOutcome run_child_process(const std::vector<std::string>& argv, const std::vector<std::string>& env,
                               const std::string& output_path, double timeout_s);

// This process's environment as "NAME=value" entries.
std::vector<std::string> current_environment();

}  // namespace clpt
