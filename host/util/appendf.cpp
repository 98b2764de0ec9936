#include "util/appendf.h"

#include <cstdarg>
#include <cstdio>

namespace clpt {

void appendf(std::string& out, const char* format, ...) {
  char buffer[1024];
  va_list args;
  va_start(args, format);
  std::vsnprintf(buffer, sizeof buffer, format, args);
  va_end(args);
  out += buffer;
}

}  // namespace clpt
