#include "repose/output/files.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <system_error>
#include <vector>

#include "repose/error.hpp"

namespace repose {

void write_file_atomically(const std::string& path, const std::string& content, FileDurability durability) {
  namespace fs = std::filesystem;
  const std::string tmp = path + ".tmp-" + std::to_string(::getpid());
  std::FILE* f = std::fopen(tmp.c_str(), "wb");
  if (!f) throw Error(path + ": cannot write: " + std::strerror(errno));
  bool written = std::fwrite(content.data(), 1, content.size(), f) == content.size();
  if (written && durability == FileDurability::synced)
    written = std::fflush(f) == 0 && ::fsync(::fileno(f)) == 0;
  const int saved_errno = errno;
  const bool closed = std::fclose(f) == 0;
  if (!written || !closed) {
    std::remove(tmp.c_str());
    throw Error(path + ": cannot write: " + std::strerror(written ? errno : saved_errno));
  }
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) {
    std::remove(tmp.c_str());
    throw Error(path + ": cannot write: " + ec.message());
  }
  if (durability == FileDurability::synced) {
    // The rename itself is durable once the directory is synced.
    const std::string dir =
        fs::path(path).parent_path().empty() ? "." : fs::path(path).parent_path().string();
    const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY);
    if (fd >= 0) {
      ::fsync(fd);
      ::close(fd);
    }
  }
}

void remove_temporaries(const std::string& path) {
  namespace fs = std::filesystem;
  const fs::path target(path);
  const fs::path dir = target.parent_path().empty() ? fs::path(".") : target.parent_path();
  const std::string prefix = target.filename().string() + ".tmp-";
  std::error_code ec;
  std::vector<fs::path> stale;
  for (const auto& entry : fs::directory_iterator(dir, ec))
    if (entry.path().filename().string().rfind(prefix, 0) == 0) stale.push_back(entry.path());
  for (const fs::path& p : stale) fs::remove(p, ec);
}

std::string read_text_file(const std::string& path, std::size_t max_bytes) {
  std::error_code ec;
  // fopen opens a directory for reading on Linux; fread then fails with a bare "I/O error".
  if (std::filesystem::is_directory(path, ec)) throw Error(path + ": cannot read: is a directory");
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) throw Error(path + ": cannot read: " + std::strerror(errno));
  std::string text;
  char buffer[1 << 16];
  std::size_t got = 0;
  while ((got = std::fread(buffer, 1, sizeof buffer, f)) > 0) {
    if (text.size() + got > max_bytes) {
      std::fclose(f);
      throw Error(path + ": cannot read: larger than " + std::to_string(max_bytes) + " bytes");
    }
    text.append(buffer, got);
  }
  const bool failed = std::ferror(f) != 0;
  std::fclose(f);
  if (failed) throw Error(path + ": cannot read: I/O error");
  return text;
}

namespace {

// Whether a file `stem`.PID can be created (and removes it): the one sure test before a run that writes there
// at its end. access() is not: it lets root by everywhere, even on /sys and read-only mounts.
bool can_create(const std::string& stem) {
  const std::string probe = stem + "-" + std::to_string(::getpid());
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0600);
  if (fd < 0) return false;
  ::close(fd);
  ::unlink(probe.c_str());
  return true;
}

}  // namespace

void ensure_output_directory(const std::string& dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::exists(dir, ec)) fs::create_directories(dir, ec);
  if (ec) throw Error(dir + ": cannot create output directory: " + ec.message());
  if (!fs::is_directory(dir, ec)) throw Error(dir + ": not a directory");
  if (::access(dir.c_str(), W_OK) != 0 || !can_create(dir + "/.repose-probe"))
    throw Error(dir + ": output directory is not writable");
}

void ensure_output_file(const std::string& path) {
  namespace fs = std::filesystem;
  const fs::path parent = fs::path(path).parent_path();
  try {
    ensure_output_directory(parent.empty() ? "." : parent.string());
  } catch (const Error& e) {
    throw Error(path + ": cannot be written: " + e.what());
  }
  std::error_code ec;
  if (fs::is_directory(path, ec)) throw Error(path + ": is a directory, not a file name");
  // The file is written as a temporary beside it, then renamed: create one now.
  if (!can_create(path + ".repose-probe")) throw Error(path + ": cannot be written: " + std::strerror(errno));
}

}  // namespace repose
