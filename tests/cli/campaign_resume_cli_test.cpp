// Resume after a kill, through the real executable: a `repose poses --out` job is killed midway, rerun, and
// must end with the result of an uninterrupted run.
//
// No clock decides these tests. "Midway" is made certain, not likely: before the job starts, the test puts a
// FIFO where the job will write its first checkpoint of the second particle (DIR/.repose-checkpoint/
// NAME.json.tmp-PID, the temporary file of an atomic write). Opening a FIFO for writing waits for a reader,
// and there is none, so the job stops there for good, with the first particle's checkpoint partly done. The
// test waits for that checkpoint (an event; the bound of 600 s only reports a hang) and kills the job. To
// know the PID before the job runs, the shell that will exec repose writes its PID and waits for a line on
// stdin.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>

#include "cli_test_support.hpp"
#include "run_cli.hpp"

extern char** environ;

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using repose::test::parse_json;
using repose::test::read_file;
using repose::test::run_cli;
using repose::test::without_timing;

using repose::test::kCampaignScale;  // fewer drops in the sanitizer build

// The job: the tetrahedron (particle 0) and the unit cube (particle 1), 20.5 items of `kChunk` drops each.
// Items run costliest first (drops x hull vertices: the cube's 8 before the tetrahedron's 4; ties in input
// order), so the cube's 20 full items come first, then the tetrahedron's, then the cube's half item: when the
// tetrahedron's first checkpoint is due, the cube's holds 20 of its 20.5 items (under MPI, with one item
// possibly still running on the other rank, at least 19).
const int kItems = 20;
const int kChunk = 100 / kCampaignScale;
const int kDrops = kItems * kChunk + kChunk / 2;
const std::string kParticles = "tetrahedron:edge=1 box:x=1,y=1,z=1";
const std::string kBlocked = "tetrahedron_edge=1";
const std::string kPartial = "box_x=1_y=1_z=1";

class CampaignResumeCli : public repose::test::TempDirTest {
 protected:
  void SetUp() override {
    TempDirTest::SetUp();
    ::setenv("OMPI_ALLOW_RUN_AS_ROOT", "1", 1);  // CI runs as root; harmless otherwise
    ::setenv("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1", 1);
  }
  void TearDown() override {
    if (pid_ > 0) {
      ::kill(-pid_, SIGKILL);  // its own process group: mpirun and its ranks too
      ::waitpid(pid_, nullptr, 0);
    }
    if (go_ >= 0) ::close(go_);
    TempDirTest::TearDown();
  }

  // Starts `launcher` + `repose ARGS` in its own process group, held before repose starts; returns the PID
  // that repose (rank 0 under mpirun) will have, or -1.
  pid_t start_held(const std::string& launcher, const std::string& args) {
    int fds[2];
    if (::pipe(fds) != 0) return -1;
    const std::string pid_file = (dir_ / "rank").string();
    // Each rank writes its PID (atomically, by rename), waits for a line on stdin (mpirun gives stdin to rank
    // 0 only; the others read end-of-file at once), then becomes repose.
    std::ofstream(dir_ / "rank.sh") << "r=${OMPI_COMM_WORLD_RANK:-0}\n"
                                    << "echo $$ >'" << pid_file << "'$r.tmp && mv '" << pid_file
                                    << "'$r.tmp '" << pid_file << "'$r\n"
                                    << "read go\n"
                                    << "exec '" << REPOSE_CLI << "' " << args << " >/dev/null 2>&1\n";
    const std::string line = "exec " + launcher + "/bin/sh '" + (dir_ / "rank.sh").string() + "'";
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_adddup2(&actions, fds[0], 0);
    posix_spawn_file_actions_addclose(&actions, fds[1]);
    posix_spawnattr_t attr;
    posix_spawnattr_init(&attr);
    posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETPGROUP);
    posix_spawnattr_setpgroup(&attr, 0);
    std::string shell = "/bin/sh", flag = "-c", text = line;
    char* argv[] = {shell.data(), flag.data(), text.data(), nullptr};
    const int rc = posix_spawn(&pid_, "/bin/sh", &actions, &attr, argv, environ);
    posix_spawn_file_actions_destroy(&actions);
    posix_spawnattr_destroy(&attr);
    ::close(fds[0]);
    go_ = fds[1];
    if (rc != 0) {
      pid_ = -1;
      return -1;
    }
    if (!wait_until([&] { return fs::exists(pid_file + "0"); })) return -1;
    return std::stoi(read_file(pid_file + "0"));
  }
  // Lets the held job run.
  void release() {
    ASSERT_EQ(::write(go_, "go\n", 3), 3);
    ::close(go_);
    go_ = -1;
  }
  // Waits until `done()` holds (true) or the job has ended (false); 600 s only report a hang.
  bool wait_until(const std::function<bool()>& done) {
    const auto hang = std::chrono::steady_clock::now() + std::chrono::seconds(600);
    while (std::chrono::steady_clock::now() < hang) {
      if (done()) return true;
      int status = 0;
      if (::waitpid(pid_, &status, WNOHANG) == pid_) {
        pid_ = -1;
        ADD_FAILURE() << "the job ended by itself, status " << status;
        return false;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    ADD_FAILURE() << "hang: nothing happened in 600 s";
    return false;
  }
  // Sends `signal` to the job and returns its wait status.
  int stop(int signal) {
    EXPECT_EQ(::kill(pid_, signal), 0);
    int status = 0;
    EXPECT_EQ(::waitpid(pid_, &status, 0), pid_);
    pid_ = -1;
    return status;
  }

  // Runs the job held at the tetrahedron's first checkpoint, stops it there with `signal`, and checks what
  // the interruption left: the cube's checkpoint, complete and partial; no result file; nothing half-written.
  int run_and_interrupt(const std::string& launcher, const std::string& args, int min_items, int signal) {
    const fs::path checkpoints = dir_ / "out/.repose-checkpoint";
    fs::create_directories(checkpoints);
    const pid_t pid = start_held(launcher, args + " --out '" + (dir_ / "out").string() + "'");
    if (pid <= 0) {
      ADD_FAILURE() << "could not start the job";
      return 0;
    }
    const fs::path fifo = checkpoints / (kBlocked + ".json.tmp-" + std::to_string(pid));
    EXPECT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    release();
    const fs::path partial = checkpoints / (kPartial + ".json");
    const bool reached = wait_until([&] {
      if (!fs::exists(partial)) return false;
      const json saved = json::parse(read_file(partial), nullptr, false);  // renamed into place: complete
      return !saved.is_discarded() && saved["n"].get<int>() >= min_items * kChunk;
    });
    if (!reached) return 0;
    const int status = stop(signal);
    const json saved = json::parse(read_file(partial));
    EXPECT_LT(saved["n"].get<int>(), kDrops) << "the checkpoint should hold part of the drops";
    EXPECT_FALSE(fs::exists(checkpoints / (kBlocked + ".json")));
    EXPECT_EQ(entries(dir_ / "out"), std::vector<std::string>{".repose-checkpoint"}) << "no result yet";
    // Every file with a final name is complete (the FIFO and any other temporary file are skipped by name).
    for (const auto& entry : fs::recursive_directory_iterator(dir_ / "out")) {
      const std::string name = entry.path().filename().string();
      if (!entry.is_regular_file() || name.find(".tmp-") != std::string::npos) continue;
      EXPECT_FALSE(json::parse(read_file(entry.path()), nullptr, false).is_discarded())
          << "partial file " << entry.path();
    }
    return status;
  }

  // The resumed run's result files equal those of an uninterrupted run, and no checkpoint is left.
  void expect_resumed_equals_whole(const std::string& resume_launcher, const std::string& args) {
    ASSERT_EQ(run_cli(args + " --out '" + (dir_ / "whole").string() + "'").exit_code, 0);
    const auto resumed = run_cli(args + " --out '" + (dir_ / "out").string() + "'", resume_launcher);
    ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
    EXPECT_EQ(entries(dir_ / "out"), entries(dir_ / "whole")) << "checkpoint left behind?";
    for (const std::string& name : {kBlocked, kPartial}) {
      const fs::path file = name + ".poses.json";
      EXPECT_EQ(without_timing(json::parse(read_file(dir_ / "out" / file))).dump(),
                without_timing(json::parse(read_file(dir_ / "whole" / file))).dump())
          << name;
    }
  }

  pid_t pid_ = -1;  // the job (the launcher under mpirun)
  int go_ = -1;     // the write end of its stdin
};

std::string job_args(int seed) {
  return "poses " + kParticles + " -n " + std::to_string(kDrops) + " --seed " + std::to_string(seed) +
         " --chunk " + std::to_string(kChunk) + " --threads 1 --no-progress";
}

// The acceptance test of resume: kill -9 midway, rerun the same command, get the uninterrupted result.
TEST_F(CampaignResumeCli, KilledRunResumesToTheUninterruptedResult) {
  const std::string args = job_args(8);
  const int status = run_and_interrupt("", args, kItems, SIGKILL);
  ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL) << "status " << status;
  expect_resumed_equals_whole("", args);
}

#ifdef REPOSE_MPIEXEC

using repose::test::mpirun;

TEST_F(CampaignResumeCli, MpiJobKilledMidwayResumesOnAnotherRankCount) {
  const std::string args = job_args(4);
  // mpirun passes SIGTERM on to every rank and waits for them (as SLURM's scancel does).
  const int status = run_and_interrupt(mpirun(2), args, kItems - 1, SIGTERM);
  ASSERT_FALSE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "the job ended normally";
  expect_resumed_equals_whole(mpirun(3), args);
}

#endif

}  // namespace
