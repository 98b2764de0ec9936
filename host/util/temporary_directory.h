// A private directory that lives as long as its owner: created empty under the system's temporary
// directory ($TMPDIR, else /tmp) and removed with everything in it when the owner is destroyed.
#pragma once

#include <string>

namespace clpt {

class TemporaryDirectory {
 public:
  // Creates "<tmp>/<prefix>-XXXXXX" (mode 0700). Throws Error(Failure) naming the path when it
  // cannot be created.
  explicit TemporaryDirectory(const std::string& prefix);
  // Removes the directory and its contents; a failure to remove is ignored (nothing to report to).
  ~TemporaryDirectory();
  TemporaryDirectory(const TemporaryDirectory&) = delete;
  TemporaryDirectory& operator=(const TemporaryDirectory&) = delete;

  const std::string& path() const { return path_; }
  // path() + "/" + name.
  std::string file(const std::string& name) const;

 private:
  std::string path_;
};

}  // namespace clpt
