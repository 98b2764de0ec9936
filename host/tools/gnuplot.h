// gnuplot as a child process: clpt draws its plots (`clpt tradeoff --plot`) by writing a gnuplot
// script and running the gnuplot found on PATH, rather than carrying a plotting library.
#pragma once

#include <functional>
#include <string>

namespace clpt {

// Full path of the first executable `gnuplot` on PATH, or "" when there is none.
std::string find_gnuplot();

// Writes the PNG `png_path` atomically: `script_for(tmp)` must return a script that draws into
// the file `tmp` (a temporary name beside png_path); gnuplot runs it, and the file is renamed to
// png_path only when gnuplot exits 0 and wrote it. gnuplot's own messages go to stderr. Throws
// Error(OutputError) naming `option` and png_path otherwise, leaving nothing behind.
void write_gnuplot_png(const std::string& gnuplot, const std::string& option, const std::string& png_path,
                       const std::function<std::string(const std::string& tmp)>& script_for);

}  // namespace clpt
