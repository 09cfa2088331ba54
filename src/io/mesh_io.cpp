// Mesh files in, STL out. Each format has its own one-pass reader (readers.hpp); this file picks it by the
// extension, reads the file, and writes binary STL.
#include "repose/io/mesh_io.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <random>
#include <string>
#include <string_view>
#include <system_error>

#include "readers.hpp"
#include "repose/error.hpp"
#include "text_scan.hpp"

namespace repose {
namespace io {

void check_vertex_count(const std::string& path, std::uint64_t count) {
  constexpr auto kMax = static_cast<std::uint64_t>(std::numeric_limits<std::int32_t>::max());
  if (count > kMax) fail(path, "too many vertices (more than " + str(kMax) + ")");
}

}  // namespace io

namespace {

using io::fail;
using io::str;

std::string errno_message(int error) { return std::error_code(error, std::generic_category()).message(); }

enum class Format { kStl, kObj, kPly, kOff, kXyz };

class FileDescriptor {
 public:
  explicit FileDescriptor(int fd) : fd_(fd) {}
  FileDescriptor(const FileDescriptor&) = delete;
  FileDescriptor& operator=(const FileDescriptor&) = delete;
  ~FileDescriptor() {
    if (fd_ >= 0) ::close(fd_);
  }
  int get() const { return fd_; }
  int release() {
    const int fd = fd_;
    fd_ = -1;
    return fd;
  }

 private:
  int fd_;
};

Format format_of(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext == ".stl") return Format::kStl;
  if (ext == ".obj") return Format::kObj;
  if (ext == ".ply") return Format::kPly;
  if (ext == ".off") return Format::kOff;
  if (ext == ".xyz") return Format::kXyz;
  const char* expected = "expected .stl, .obj, .ply, .off, .xyz";
  if (ext.empty()) fail(path, std::string("unsupported format (no file extension; ") + expected + ")");
  fail(path, "unsupported format '" + ext + "' (" + expected + ")");
}

// A bound that keeps every offset and count far from overflow; real particle meshes are far smaller.
constexpr std::uint64_t kMaxFileSize = std::numeric_limits<std::uint32_t>::max();

// Opens `path`, checks that it is not a directory and that its extension names a supported `format`, and
// returns its bytes.
std::string read_file(const std::string& path, Format& format) {
  const FileDescriptor file(::open(path.c_str(), O_RDONLY | O_CLOEXEC));
  if (file.get() < 0) fail(path, "cannot open: " + errno_message(errno));
  struct stat st {};
  if (::fstat(file.get(), &st) != 0) fail(path, "cannot open: " + errno_message(errno));
  if (S_ISDIR(st.st_mode)) fail(path, "cannot open: " + errno_message(EISDIR));
  format = format_of(path);
  if (static_cast<std::uint64_t>(st.st_size) > kMaxFileSize) {
    fail(path, "file too large (" + str(st.st_size) + " bytes; at most " + str(kMaxFileSize) + ")");
  }
  std::string data;
  data.reserve(static_cast<std::size_t>(st.st_size));
  char buffer[1 << 16];
  for (;;) {
    const ssize_t n = ::read(file.get(), buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) fail(path, "cannot read: " + errno_message(errno));
    if (n == 0) break;
    data.append(buffer, static_cast<std::size_t>(n));
    if (data.size() > kMaxFileSize) fail(path, "file too large (more than " + str(kMaxFileSize) + " bytes)");
  }
  return data;
}

void append_le32(std::string& out, std::uint32_t v) {
  for (int b = 0; b < 4; ++b) out.push_back(static_cast<char>((v >> (8 * b)) & 0xFF));
}

void append_float(std::string& out, double v) {
  const auto f = static_cast<float>(v);
  std::uint32_t bits = 0;
  std::memcpy(&bits, &f, sizeof bits);
  append_le32(out, bits);
}

// Parses the bytes of a mesh file; `path` names it in errors.
TriangleMesh parse_mesh(const std::string& path, std::string_view data, Format format) {
  if (data.empty()) fail(path, "empty file");
  TriangleMesh mesh;
  switch (format) {
    case Format::kStl:
      mesh = io::read_stl(path, data);
      break;
    case Format::kObj:
      mesh = io::read_obj(path, data);
      break;
    case Format::kPly:
      mesh = io::read_ply(path, data);
      break;
    case Format::kOff:
      mesh = io::read_off(path, data);
      break;
    case Format::kXyz:
      mesh = io::read_xyz(path, data);
      break;
  }
  if (mesh.vertices.empty()) fail(path, "no vertices");
  return mesh;
}

}  // namespace

TriangleMesh read_mesh(const std::string& path) {
  Format format = Format::kStl;
  const std::string data = read_file(path, format);
  return parse_mesh(path, data, format);
}

TriangleMesh read_mesh_from_memory(const std::string& bytes, const std::string& name) {
  const Format format = format_of(name);
  if (bytes.size() > kMaxFileSize) {
    fail(name, "file too large (" + str(bytes.size()) + " bytes; at most " + str(kMaxFileSize) + ")");
  }
  return parse_mesh(name, bytes, format);
}

namespace {

// Writes `out` to a sibling temporary and renames it over `path`, so readers never see a partial file. O_EXCL
// with a random suffix avoids clobbering a concurrent writer's temporary; mode 0666 lets the umask decide.
void write_atomically(const std::string& out, const std::string& path) {
  std::random_device entropy;
  std::string tmp;
  int fd = -1;
  for (int attempt = 0; attempt < 16 && fd < 0; ++attempt) {
    char suffix[16];
    std::snprintf(suffix, sizeof suffix, ".tmp-%08x", static_cast<unsigned>(entropy()));
    tmp = path + suffix;
    fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd < 0 && errno != EEXIST) break;
  }
  if (fd < 0) fail(path, "cannot write: " + errno_message(errno));
  FileDescriptor file(fd);
  auto give_up = [&](const std::string& reason) {
    ::unlink(tmp.c_str());
    fail(path, "cannot write: " + reason);
  };
  for (std::size_t done = 0; done < out.size();) {
    const ssize_t n = ::write(file.get(), out.data() + done, out.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) give_up(errno_message(errno));
    done += static_cast<std::size_t>(n);
  }
  if (::fsync(file.get()) != 0) give_up(errno_message(errno));
  if (::close(file.release()) != 0) give_up(errno_message(errno));
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) give_up(ec.message());
}

// Every triangle's indices name vertices of the mesh.
void check_indices(const TriangleMesh& mesh, const std::string& path) {
  const auto n_vertices = mesh.vertices.size();
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
    for (const std::int32_t i : mesh.triangles[t])
      if (i < 0 || static_cast<std::size_t>(i) >= n_vertices)
        fail(path, "cannot write: in triangle " + str(t) + ", vertex index " + std::to_string(i) +
                       " does not exist (" + str(n_vertices) + " vertices)");
}

}  // namespace

void write_stl(const TriangleMesh& mesh, const std::string& path) {
  check_indices(mesh, path);
  if (mesh.triangles.size() > std::numeric_limits<std::uint32_t>::max()) {
    fail(path, "cannot write: too many triangles for STL");
  }
  std::string out = "binary STL written by repose";
  out.resize(80, ' ');
  append_le32(out, static_cast<std::uint32_t>(mesh.triangles.size()));
  out.reserve(84 + 50 * mesh.triangles.size());
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const Triangle& tri = mesh.triangles[t];
    const Vec3& a = mesh.vertices[tri[0]];
    const Vec3 normal = (mesh.vertices[tri[1]] - a).cross(mesh.vertices[tri[2]] - a).normalized();
    for (int k = 0; k < 3; ++k) append_float(out, std::isfinite(normal[k]) ? normal[k] : 0.0);
    for (const std::int32_t i : tri) {
      for (int k = 0; k < 3; ++k) append_float(out, mesh.vertices[i][k]);
    }
    out.append(2, '\0');  // attribute byte count
  }
  write_atomically(out, path);
}

void write_obj(const TriangleMesh& mesh, const std::string& path) {
  check_indices(mesh, path);
  std::string out = "# OBJ written by repose\n";
  char line[128];
  for (const Vec3& v : mesh.vertices) {
    // %.17g: every double read back to the same bits.
    std::snprintf(line, sizeof line, "v %.17g %.17g %.17g\n", v[0], v[1], v[2]);
    out += line;
  }
  for (const Triangle& t : mesh.triangles) {
    std::snprintf(line, sizeof line, "f %d %d %d\n", t[0] + 1, t[1] + 1, t[2] + 1);
    out += line;
  }
  write_atomically(out, path);
}

}  // namespace repose
