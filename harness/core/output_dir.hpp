// Output directories written whole or not at all: built in a staging directory beside the target,
// then swapped into place, so that a reader (or a failed run) never leaves a half-written mix.
#pragma once

#include <string>

namespace dropcheck {

// Throws InputError unless `dir` is absent, empty, or holds only what a report writes (README.md
// and *.svg files): dropcheck refuses to replace a directory it did not write.
void check_replaceable(const std::string& dir);

class StagingDir {
 public:
  // Creates an empty directory beside `target` (".<name>.staging-<pid>"). Throws InputError.
  explicit StagingDir(const std::string& target);
  // Removes the staging directory and its content unless commit() succeeded.
  ~StagingDir();
  StagingDir(const StagingDir&) = delete;
  StagingDir& operator=(const StagingDir&) = delete;

  const std::string& path() const { return path_; }

  // Replaces the target with the staging directory: target -> backup, staging -> target, then the
  // backup is removed (on failure the backup is moved back). Throws InputError.
  void commit();

 private:
  std::string target_, path_;
  bool committed_ = false;
};

}  // namespace dropcheck
