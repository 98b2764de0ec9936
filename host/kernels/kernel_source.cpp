#include "kernels/kernel_source.h"

#include <set>
#include <sstream>

#include "util/error.h"

namespace clpt {
namespace {

const char* find_embedded(const std::string& name) {
  for (const EmbeddedFile& f : embedded_kernel_files())
    if (name == f.name) return f.text;
  return nullptr;
}

// `#include "name"` -> name, or "" when the line is not such an include.
std::string included_name(const std::string& line) {
  const size_t hash = line.find_first_not_of(" \t");
  if (hash == std::string::npos || line.compare(hash, 8, "#include") != 0) return "";
  const size_t open = line.find('"', hash + 8);
  const size_t close = open == std::string::npos ? open : line.find('"', open + 1);
  if (close == std::string::npos) return "";
  return line.substr(open + 1, close - open - 1);
}

void expand(const std::string& name, std::set<std::string>& done, std::ostringstream& out) {
  if (!done.insert(name).second) return;
  const char* text = find_embedded(name);
  if (!text) throw Error(ExitCode::Failure, "kernel source '" + name + "' is not embedded in clpt");
  std::istringstream in(text);
  std::string line;
  int line_number = 0;
  out << "#line 1 \"" << name << "\"\n";
  while (std::getline(in, line)) {
    ++line_number;
    const std::string include = included_name(line);
    if (include.empty()) {
      out << line << '\n';
      continue;
    }
    expand(include, done, out);
    out << "#line " << line_number + 1 << " \"" << name << "\"\n";
  }
}

}  // namespace

std::string assemble_kernel_source(const std::string& entry_file) {
  std::set<std::string> done;
  std::ostringstream out;
  expand(entry_file, done, out);
  return out.str();
}

}  // namespace clpt
