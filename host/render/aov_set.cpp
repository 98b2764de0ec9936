// Parsing and printing the set of first-hit layers (render/aov_set.h).
#include "render/aov_set.h"

#include "util/error.h"

namespace clpt {

std::string aov_set_text(const AovSet& set) {
  std::string out;
  auto add = [&out](bool on, const char* name) {
    if (!on) return;
    if (!out.empty()) out += ",";
    out += name;
  };
  add(set.albedo, "albedo");
  add(set.normal, "normal");
  add(set.depth, "depth");
  return out;
}

AovSet parse_aov_set(const std::string& list, const std::string& what) {
  AovSet set;
  size_t begin = 0;
  for (;;) {
    const size_t comma = list.find(',', begin);
    const std::string word = list.substr(begin, comma == std::string::npos ? std::string::npos : comma - begin);
    bool* slot = word == "albedo" ? &set.albedo : word == "normal" ? &set.normal : word == "depth" ? &set.depth : nullptr;
    if (!slot)
      throw Error(ExitCode::Usage, what + ": '" + word +
                                       "' is not a layer; the layers are albedo, normal and depth (a comma list)");
    if (*slot) throw Error(ExitCode::Usage, what + ": '" + word + "' is named twice");
    *slot = true;
    if (comma == std::string::npos) break;
    begin = comma + 1;
  }
  return set;
}

}  // namespace clpt
