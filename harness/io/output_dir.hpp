// Output folders (the report) written whole or not at all: built in a uniquely named staging folder
// beside the target, then swapped into place in one rename, so that a reader, a failed or killed
// run, or a second run writing the same folder never leaves a half-written mix. A folder dropcheck
// wrote carries a manifest (kManifestName) listing its files; dropcheck replaces no other folder.
#pragma once

#include <memory>
#include <string>

namespace dropcheck {

class CleanupOnSignal;

// The manifest's file name inside a report folder.
inline constexpr const char* kManifestName = ".dropcheck-manifest";

// Throws InputError (key "--out") unless `dir` is absent, empty, or holds only what dropcheck
// wrote: the files its manifest lists, or, for a report written before manifests existed, a
// README.md that starts "# dropcheck comparison report" plus *.svg files that README.md names.
void check_replaceable(const std::string& dir);

class StagingDir {
 public:
  // Creates an empty folder beside `target` (".<name>.staging-XXXXXX", a symbolic link followed to
  // the folder it names) and registers it for removal on SIGINT/SIGTERM. Throws InputError.
  explicit StagingDir(const std::string& target);
  // Removes the staging folder and its content unless commit() succeeded.
  ~StagingDir();
  StagingDir(const StagingDir&) = delete;
  StagingDir& operator=(const StagingDir&) = delete;

  const std::string& path() const { return path_; }

  // Writes the manifest (every file now in the staging folder), checks the target is still
  // replaceable, then exchanges staging and target in one rename (renameat2 RENAME_EXCHANGE) and
  // removes what was the target. Throws InputError, leaving the target as it was.
  void commit();

 private:
  std::string target_, path_;
  std::unique_ptr<CleanupOnSignal> cleanup_;
  bool committed_ = false;
};

}  // namespace dropcheck
