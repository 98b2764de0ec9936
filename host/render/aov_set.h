// The first-hit layers a render adds to its EXR for denoisers (`clpt render --aovs`; kernels/aov.cl
// records them, render/film.h accumulates them, io/render_file.h names their channels;
// docs/aovs.md): which of albedo, normal and depth were asked for.
#pragma once

#include <string>

namespace clpt {

struct AovSet {
  bool albedo = false;
  bool normal = false;
  bool depth = false;
  bool any() const { return albedo || normal || depth; }
};

// "albedo,normal,depth" (those in the set, in that order); "" for none.
std::string aov_set_text(const AovSet& set);

// A comma-separated list of albedo, normal and depth (each at most once, in any order).
// Throws Error(Usage) beginning with `what` (e.g. "--aovs albedo,nrm") naming a word it does not
// know, a repeated one or an empty list.
AovSet parse_aov_set(const std::string& list, const std::string& what);

}  // namespace clpt
