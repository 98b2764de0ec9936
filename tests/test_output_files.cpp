// Output files (util/atomic_file.h and the writers built on it): a bare file name goes in the
// current directory; a file that cannot be written at the end of a command (its name taken by a
// directory, what no check before the work could foresee for a directory made meanwhile) fails
// with the output error naming the path, and leaves neither the file nor a temporary behind.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>

#include "render/film.h"
#include "render/film_raw.h"
#include "util/atomic_file.h"
#include "util/error.h"
#include "util/temporary_directory.h"

namespace clpt {
namespace {

namespace fs = std::filesystem;

// Names of the entries of `dir`, sorted.
std::vector<std::string> entries(const fs::path& dir) {
  std::vector<std::string> out;
  for (const auto& e : fs::directory_iterator(dir)) out.push_back(e.path().filename().string());
  std::sort(out.begin(), out.end());
  return out;
}

// Runs `write`, which must throw Error(OutputError) naming `path`.
template <typename Write>
void expect_output_error(const std::string& path, Write write) {
  try {
    write();
    FAIL() << "no error writing " << path;
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::OutputError) << e.what();
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
}

TEST(OutputFiles, DirectoryOfABareNameIsTheCurrentOne) {
  EXPECT_EQ(directory_of("out.exr"), fs::path("."));
  EXPECT_EQ(directory_of("renders/out.exr"), fs::path("renders"));
  EXPECT_EQ(directory_of("/out.exr"), fs::path("/"));
  EXPECT_EQ(fs::absolute(directory_of("out.exr")), fs::absolute("."));  // what once threw
}

TEST(OutputFiles, CheckRefusesWhatCannotBeWrittenAndLeavesNothing) {
  const TemporaryDirectory dir("clpt-output-files");
  const fs::path root = dir.path();
  std::FILE* f = std::fopen((root / "afile").c_str(), "wb");
  ASSERT_NE(f, nullptr);
  std::fclose(f);
  fs::create_directory(root / "adir");
  const std::vector<std::string> before = entries(root);
  check_output_file("-o", (root / "out.exr").string());  // writable: no error, no file
  for (const fs::path& bad : {root / "afile" / "out.exr", root / "nowhere" / "out.exr", root / "adir"})
    expect_output_error("-o " + bad.string(), [&] { check_output_file("-o", bad.string()); });
  EXPECT_EQ(entries(root), before);
}

TEST(OutputFiles, AWriteThatFailsAtTheEndLeavesNoTemporary) {
  const TemporaryDirectory dir("clpt-output-files");
  const fs::path root = dir.path();
  fs::create_directory(root / "taken.json");
  fs::create_directory(root / "taken.pfm");
  const std::vector<std::string> before = entries(root);
  const std::string json = (root / "taken.json").string();
  expect_output_error(json, [&] { write_file_atomically(json, "{}\n", "--json"); });
  Film film(4, 3);
  const std::string pfm = (root / "taken.pfm").string();
  expect_output_error(pfm, [&] { write_film_pfm(pfm, film); });
  EXPECT_EQ(entries(root), before);
}

}  // namespace
}  // namespace clpt
