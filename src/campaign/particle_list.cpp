// Which particles a job covers: files, directories of meshes, shape specs and manifest files.
#include <algorithm>
#include <cctype>
#include <filesystem>
#include <map>

#include "repose/campaign/campaign.hpp"
#include "repose/error.hpp"
#include "repose/geometry/shapes.hpp"
#include "repose/output/files.hpp"

namespace repose {

namespace {

namespace fs = std::filesystem;

bool is_mesh_file(const fs::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext == ".stl" || ext == ".obj" || ext == ".ply" || ext == ".off";
}

// A name that is safe as a file name: letters, digits and . _ - = kept, anything else becomes '_'.
std::string file_safe(const std::string& text) {
  std::string name = text;
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '_' && c != '-' && c != '=') c = '_';
  if (name.empty() || name[0] == '.') name = std::string("_") += name;
  return name;
}

void add_input(const std::string& input, std::vector<std::string>& sources) {
  std::error_code ec;
  if (!is_shape_spec(input) && fs::is_directory(input, ec)) {
    std::vector<std::string> meshes;
    for (const auto& entry : fs::directory_iterator(input, ec))
      if (entry.is_regular_file(ec) && is_mesh_file(entry.path())) meshes.push_back(entry.path().string());
    if (ec) throw Error(input + ": cannot list directory: " + ec.message());
    if (meshes.empty()) throw Error(input + ": no mesh files (.stl, .obj, .ply, .off) in this directory");
    std::sort(meshes.begin(), meshes.end());
    sources.insert(sources.end(), meshes.begin(), meshes.end());
  } else {
    sources.push_back(input);
  }
}

}  // namespace

std::vector<CampaignParticle> resolve_particles(const std::vector<std::string>& inputs,
                                                const std::string& manifest) {
  std::vector<std::string> sources;
  for (const std::string& input : inputs) add_input(input, sources);
  if (!manifest.empty()) {
    const std::string text = read_text_file(manifest, std::size_t{64} << 20);
    const fs::path base = fs::path(manifest).parent_path();
    std::size_t start = 0;
    for (int line_no = 1; start < text.size(); ++line_no) {
      std::size_t end = text.find('\n', start);
      if (end == std::string::npos) end = text.size();
      std::string line = text.substr(start, end - start);
      start = end + 1;
      const auto first = line.find_first_not_of(" \t\r");
      if (first == std::string::npos || line[first] == '#') continue;
      line = line.substr(first, line.find_last_not_of(" \t\r") - first + 1);
      // A relative path is relative to the manifest; anything that is not a file there (a shape spec, or a
      // path that does not exist, reported when it is loaded) is taken as written.
      std::error_code ec;
      if (!is_shape_spec(line) && fs::path(line).is_relative() && fs::exists(base / line, ec))
        line = (base / line).string();
      add_input(line, sources);
    }
  }
  if (sources.empty()) throw Error("no particles given (mesh files, directories, shape specs or --manifest)");

  std::vector<CampaignParticle> particles;
  std::map<std::string, std::string> seen;  // name → source
  for (const std::string& source : sources) {
    const std::string name = file_safe(is_shape_spec(source) ? source : fs::path(source).stem().string());
    const auto [it, fresh] = seen.emplace(name, source);
    if (!fresh)
      throw Error("two particles named '" + name + "' (" + it->second + " and " + source +
                  "): results are written per name; rename one");
    particles.push_back({name, source});
  }
  return particles;
}

}  // namespace repose
