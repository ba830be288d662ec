#include "harness/core/atomic_file.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "harness/core/input_error.hpp"

namespace dropcheck {

void write_file_atomic(const std::string& path, const std::string& content) {
  const std::filesystem::path target(path);
  std::error_code ec;
  if (target.has_parent_path()) std::filesystem::create_directories(target.parent_path(), ec);
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw InputError(path, 0, "", std::string("cannot write: ") + std::strerror(errno));
    out << content;
    out.close();
    if (!out) {
      std::filesystem::remove(tmp, ec);
      throw InputError(path, 0, "", "write failed");
    }
  }
  std::filesystem::rename(tmp, target, ec);
  if (ec) {
    const std::string why = ec.message();  // before remove() overwrites ec
    std::filesystem::remove(tmp, ec);
    throw InputError(path, 0, "", "cannot replace the file: " + why);
  }
}

}  // namespace dropcheck
