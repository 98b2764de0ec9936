#include "render/film_raw.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>

#include "util/atomic_file.h"
#include "util/error.h"

namespace clpt {

void write_pfm_atomic(const std::string& path, int width, int height, const std::vector<float>& rgb) {
  const std::string tmp = temporary_path_for(path);
  {
    std::ofstream out(tmp, std::ios::binary);
    if (!out) throw Error(ExitCode::OutputError, path + ": cannot write output: " + std::strerror(errno));
    // Negative scale: little-endian floats. PFM rows run bottom to top.
    out << "PF\n" << width << " " << height << "\n-1.0\n";
    for (int row = height - 1; row >= 0; --row)
      out.write(reinterpret_cast<const char*>(&rgb[size_t(row) * width * 3]),
                std::streamsize(sizeof(float)) * width * 3);
    if (!out.flush()) {
      std::remove(tmp.c_str());
      throw Error(ExitCode::OutputError, path + ": cannot write output: write failed");
    }
  }
  commit_temporary(tmp, path);
}

void write_film_pfm(const std::string& path, const Film& film) {
  std::string variance_path = path;
  const size_t dot = variance_path.rfind(".pfm");
  variance_path = (dot == std::string::npos ? variance_path : variance_path.substr(0, dot)) + ".var.pfm";
  write_pfm_atomic(variance_path, film.width(), film.height(), film.variance_rgb());
  write_pfm_atomic(path, film.width(), film.height(), film.mean_rgb());
}

}  // namespace clpt
