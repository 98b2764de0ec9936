#include "scene/precision_preset.h"

namespace clpt {

const char* precision_name(Precision precision) {
  switch (precision) {
    case Precision::Fast: return "fast";
    case Precision::Double: return "double";
    default: return "robust";
  }
}

std::optional<Precision> parse_precision(const std::string& name) {
  if (name == "fast") return Precision::Fast;
  if (name == "robust") return Precision::Robust;
  if (name == "double") return Precision::Double;
  return std::nullopt;
}

}  // namespace clpt
