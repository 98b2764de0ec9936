// printf-style formatting appended to a std::string, for the reports commands print (compare,
// verify). One line may be at most 1023 characters; longer output is cut there.
#pragma once

#include <string>

namespace clpt {

__attribute__((format(printf, 2, 3))) void appendf(std::string& out, const char* format, ...);

}  // namespace clpt
