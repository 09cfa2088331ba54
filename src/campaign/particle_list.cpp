// Which particles a job covers: files, directories of meshes, shape specs and manifest files.
#include <algorithm>
#include <cctype>
#include <cmath>
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
  return ext == ".stl" || ext == ".obj" || ext == ".ply" || ext == ".off" || ext == ".xyz";
}

struct Source {
  std::string path;
  MeshOptions mesh;
};

// "X,Y,Z": three finite numbers (a line's --com).
Vec3 parse_point(const std::string& text) {
  Vec3 p;
  std::size_t pos = 0;
  for (int k = 0; k < 3; ++k) {
    const std::size_t end = k < 2 ? text.find(',', pos) : text.size();
    const std::string part = end == std::string::npos ? "" : text.substr(pos, end - pos);
    std::size_t used = 0;
    double x = NAN;
    try {
      x = std::stod(part, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (part.empty() || used != part.size() || !std::isfinite(x))
      throw Error("option --com must be X,Y,Z (three finite numbers), got '" + text + "'");
    p[k] = x;
    pos = end + 1;
  }
  return p;
}

// The options after a manifest line's path ("--mesh-units mm --repair"), on top of `mesh`.
MeshOptions parse_line_options(const std::string& text, MeshOptions mesh, bool lengths_in_cm,
                               const std::string& where) {
  std::vector<std::string> words;
  for (std::size_t pos = 0; pos < text.size();) {
    const std::size_t begin = text.find_first_not_of(" \t", pos);
    if (begin == std::string::npos) break;
    const std::size_t end = std::min(text.find_first_of(" \t", begin), text.size());
    words.push_back(text.substr(begin, end - begin));
    pos = end;
  }
  bool scale_given = false, units_given = false;
  for (std::size_t i = 0; i < words.size(); ++i) {
    const std::string& w = words[i];
    const auto value = [&]() -> const std::string& {
      if (i + 1 >= words.size()) throw Error(where + "option " + w + " needs a value");
      return words[++i];
    };
    try {
      if (w == "--repair") {
        mesh.repair = true;
      } else if (w == "--largest-component") {
        mesh.largest_component = true;
      } else if (w == "--inertia") {
        mesh.inertia = parse_inertia_model(value());
      } else if (w == "--mesh-units") {
        mesh.scale = mesh_unit_scale(value(), lengths_in_cm);
        units_given = true;
      } else if (w == "--com") {
        mesh.center_of_mass = parse_point(value());
      } else if (w == "--scale") {
        const std::string& v = value();
        std::size_t used = 0;
        double scale = 0;
        try {
          scale = std::stod(v, &used);
        } catch (const std::exception&) {
          used = 0;
        }
        if (used != v.size() || !std::isfinite(scale) || scale <= 0)
          throw Error("option --scale must be a finite positive number, got '" + v + "'");
        mesh.scale = scale;
        scale_given = true;
      } else {
        throw Error("unknown option '" + w +
                    "' (a manifest line takes --scale, --mesh-units, --inertia, --repair, "
                    "--largest-component, --com)");
      }
    } catch (const Error& e) {
      const std::string message = e.what();
      throw Error(message.rfind(where, 0) == 0 ? message : where + message);
    }
  }
  if (scale_given && units_given) throw Error(where + "give either --scale or --mesh-units, not both");
  return mesh;
}

// A name that is safe as a file name: letters, digits and . _ - = kept, anything else becomes '_'.
std::string file_safe(const std::string& text) {
  std::string name = text;
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '_' && c != '-' && c != '=') c = '_';
  if (name.empty() || name[0] == '.') name = std::string("_") += name;
  return name;
}

void add_input(const std::string& input, const MeshOptions& mesh, std::vector<Source>& sources) {
  std::error_code ec;
  if (!is_shape_spec(input) && fs::is_directory(input, ec)) {
    std::vector<std::string> meshes;
    for (const auto& entry : fs::directory_iterator(input, ec))
      if (entry.is_regular_file(ec) && is_mesh_file(entry.path())) meshes.push_back(entry.path().string());
    if (ec) throw Error(input + ": cannot list directory: " + ec.message());
    if (meshes.empty())
      throw Error(input + ": no mesh files (.stl, .obj, .ply, .off, .xyz) in this directory");
    std::sort(meshes.begin(), meshes.end());
    for (const std::string& m : meshes) sources.push_back({m, mesh});
  } else {
    sources.push_back({input, mesh});
  }
}

}  // namespace

std::vector<CampaignParticle> resolve_particles(const std::vector<std::string>& inputs,
                                                const std::string& manifest, const MeshOptions& mesh,
                                                bool lengths_in_cm) {
  std::vector<Source> sources;
  for (const std::string& input : inputs) add_input(input, mesh, sources);
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
      // Options follow the path, from the first " --" on (a path may hold spaces).
      MeshOptions line_mesh = mesh;
      if (const std::size_t options = line.find(" --"); options != std::string::npos) {
        line_mesh = parse_line_options(line.substr(options), mesh, lengths_in_cm,
                                       manifest + ": line " + std::to_string(line_no) + ": ");
        line = line.substr(0, line.find_last_not_of(" \t", options) + 1);
      }
      // A relative path is relative to the manifest; anything that is not a file there (a shape spec, or a
      // path that does not exist, reported when it is loaded) is taken as written.
      std::error_code ec;
      if (!is_shape_spec(line) && fs::path(line).is_relative() && fs::exists(base / line, ec))
        line = (base / line).string();
      add_input(line, line_mesh, sources);
    }
  }
  if (sources.empty()) throw Error("no particles given (mesh files, directories, shape specs or --manifest)");

  std::vector<CampaignParticle> particles;
  std::map<std::string, std::string> seen;  // name → source
  for (const Source& source : sources) {
    const std::string& path = source.path;
    const std::string name = file_safe(is_shape_spec(path) ? path : fs::path(path).stem().string());
    const auto [it, fresh] = seen.emplace(name, path);
    if (!fresh)
      throw Error("two particles named '" + name + "' (" + it->second + " and " + path +
                  "): results are written per name; rename one");
    particles.push_back({name, path, source.mesh});
  }
  return particles;
}

}  // namespace repose
