// Output files are written whole or not at all: into a uniquely named temporary beside the target
// (removed again on failure or on SIGINT/SIGTERM/SIGHUP), then renamed over it. Only a regular file
// is ever replaced; a symbolic link is written through, to the file it points to.
#pragma once

#include <filesystem>
#include <functional>
#include <ostream>
#include <string>

#include "harness/io/link_policy.hpp"

namespace dropcheck {

// Where a write to `path` lands: `path` itself, or, for a symbolic link, the file it finally
// points to (relative links resolved from the link's folder). Throws InputError, prefixed by `key`
// ("--csv"), when that is something other than a regular file or nothing (a folder, a device, a
// FIFO, a socket), or a link loop. With Links::refuse a symbolic link at `path` is refused too
// (an entry of a folder dropcheck fills: never written through).
std::filesystem::path output_target(const std::string& path, const std::string& key = "",
                                    Links links = Links::follow);

// Throws InputError, prefixed by `key`, when `path` does not lie below `root`, or when a folder on
// the way from `root` (the user's own: a link there is followed) down to `path`'s folder is a
// symbolic link or not a folder. Folders not yet made pass: they are made as folders. An entry of a
// folder dropcheck fills at depth (a cache's subfolders) is checked so before it is read or
// written.
void check_no_links_below(const std::filesystem::path& root, const std::filesystem::path& path,
                          const std::string& key);

// Writes `content` to output_target(path) atomically, creating missing parent folders. Throws
// InputError naming the path when it cannot; the previous file is then untouched. With
// Links::refuse a link at `path` is refused, and the rename replaces the entry itself: a link
// planted after the check is replaced, never written through.
void write_file_atomic(const std::string& path, const std::string& content,
                       Links links = Links::follow);

// The same with the content streamed: `fill` writes it into a buffered stream over the temporary
// file (64 KiB at a time), so that a large output is never held in memory whole. When `fill`
// throws, the temporary is removed and the exception passed on; a write error is an InputError.
void write_file_atomic(const std::string& path, const std::function<void(std::ostream&)>& fill,
                       Links links = Links::follow);

}  // namespace dropcheck
