// `repose settle --vtk DIR` with --frame-dt and --frames: the frames written and the times listed in
// settling.pvd follow the requested spacing and count.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli_test_support.hpp"
#include "run_cli.hpp"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using repose::test::parse_json;
using repose::test::read_file;
using repose::test::run_cli;
using repose::test::shell_quote;

class SettleVtkCli : public repose::test::TempDirTest {
 protected:
  // The tilted tetrahedron (cgs), 0.043 s to rest, with ParaView output in dir_/vtk.
  json run(const std::string& options) {
    return parse_json(
        run_cli("settle tetrahedron:edge=1 --density 1.2 --units cgs --orientation axis-angle:1,0.3,0,2.5 "
                "--json --vtk " +
                shell_quote((dir_ / "vtk").string()) + " " + options));
  }
  // The times listed in settling.pvd, checked against the files: one particle_NNNNN.vtp per entry, in order,
  // each carrying the same time as its TimeValue.
  std::vector<double> frame_times() {
    const std::string pvd = read_file(dir_ / "vtk/settling.pvd");
    // Each entry: <DataSet timestep="T" ... file="NAME"/> (found by hand: GCC 12's std::regex trips
    // -Wmaybe-uninitialized in the sanitizer build).
    auto attribute = [](const std::string& text, std::size_t from, const std::string& key) {
      const std::size_t at = text.find(key + "=\"", from);
      if (at == std::string::npos) return std::string();
      const std::size_t begin = at + key.size() + 2;
      return text.substr(begin, text.find('"', begin) - begin);
    };
    std::vector<double> times;
    for (std::size_t at = pvd.find("timestep=\""); at != std::string::npos;
         at = pvd.find("timestep=\"", at + 1)) {
      const std::string time = attribute(pvd, at, "timestep"), file = attribute(pvd, at, "file");
      char name[32];
      std::snprintf(name, sizeof name, "particle_%05zu.vtp", times.size());
      EXPECT_EQ(file, name);
      const std::string vtp = read_file(dir_ / "vtk" / name);
      EXPECT_NE(vtp.find("Name=\"TimeValue\" NumberOfTuples=\"1\" format=\"ascii\">" + time + "<"),
                std::string::npos)
          << name;
      times.push_back(std::stod(time));
    }
    std::size_t files = 0;
    for (const std::string& name : entries(dir_ / "vtk")) files += name.starts_with("particle_");
    EXPECT_EQ(files, times.size()) << "a frame file not listed in settling.pvd, or the reverse";
    return times;
  }
};

TEST_F(SettleVtkCli, FrameDtSpacesTheFrames) {
  // A frame at t = 0, then at the first step at least frame_dt after the last frame, then the final state:
  // every gap but the last is in [frame_dt, frame_dt + dt], the last is at most that, and the count follows.
  const double frame_dt = 0.005;
  const json j = run("--frame-dt 0.005");
  ASSERT_EQ(j["status"], "rest");
  const double t = j["time_to_rest"].get<double>(), dt = j["parameters"]["dt"].get<double>();
  const std::vector<double> times = frame_times();
  ASSERT_GE(times.size(), 2u);
  EXPECT_EQ(times.front(), 0.0);
  EXPECT_EQ(times.back(), t);  // written exactly (shortest round-trip representation)
  for (std::size_t i = 1; i + 1 < times.size(); ++i) {
    EXPECT_GE(times[i] - times[i - 1], frame_dt * (1 - 1e-12)) << "frame " << i;
    EXPECT_LE(times[i] - times[i - 1], frame_dt + dt * (1 + 1e-9)) << "frame " << i;
  }
  EXPECT_GT(times.back(), times[times.size() - 2]);
  EXPECT_LE(times.back() - times[times.size() - 2], frame_dt + dt * (1 + 1e-9));
  // 0.043 s at 0.005 s: frames at 0, ~0.005, ..., ~0.040 and the rest at 0.043.
  EXPECT_EQ(times.size(), 10u);
}

TEST_F(SettleVtkCli, FramesSpreadThatManyFramesOverTheRun) {
  // --frames N: exactly N frames, from 0 to the rest, the inner ones about T/(N − 1) apart (the first step at
  // least that far from the previous frame).
  const int n = 7;
  const json j = run("--frames 7");
  ASSERT_EQ(j["status"], "rest");
  const double t = j["time_to_rest"].get<double>(), dt = j["parameters"]["dt"].get<double>();
  const std::vector<double> times = frame_times();
  ASSERT_EQ(times.size(), static_cast<std::size_t>(n));
  EXPECT_EQ(times.front(), 0.0);
  EXPECT_EQ(times.back(), t);
  const double spacing = t / (n - 1);
  for (int i = 1; i + 1 < n; ++i) {
    EXPECT_GE(times[i] - times[i - 1], spacing * (1 - 1e-12)) << "frame " << i;
    EXPECT_LE(times[i] - times[i - 1], spacing + dt * (1 + 1e-9)) << "frame " << i;
  }
  EXPECT_GT(times[n - 1], times[n - 2]);
  // The markers series has the same frames.
  std::size_t markers = 0;
  for (const std::string& name : entries(dir_ / "vtk")) markers += name.starts_with("markers_");
  EXPECT_EQ(markers, static_cast<std::size_t>(n));
  EXPECT_TRUE(fs::exists(dir_ / "vtk/wall.vtp"));
}

// --frames with --frame-dt is refused (the synopsis offers one or the other): first_hour_cli_test.cpp.

}  // namespace
