// SPDX-License-Identifier: GPL-3.0-or-later
// A rank of a distributed run that dies alone (what the system's out-of-memory killer or a lost
// node does: SIGKILL to one rank's process, rank 0 or another) stops the run on every rank:
// mpirun exits non-zero within seconds and names the rank, no rank is left waiting for the
// dead one, the frames written before stay readable, and results.h5 is not marked complete.
// (A rank that fails with an error of its own prints it with its rank and calls MPI_Abort:
// tools/femdem/main.cpp; the same stop.)
#include <fcntl.h>
#include <gtest/gtest.h>
#include <hdf5.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "support/run_outputs.hpp"
#include "support/vibrating_bar_scene.hpp"

extern char** environ;

namespace femdem::test {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// An elastic bar that vibrates for far longer than the test waits (17,500 steps, about 20 s in
// the release build): a frame every 18 steps.
const std::string kLongBar = vibrating_bar_scene("distributed: a rank dies", R"(
end_time = 200.0
output_interval = 0.2
history_interval = 0.1
)");

fs::path tmp_dir() {
  return fs::path(FEMDEM_TEST_TMP) / "distributed_failure";
}

// The parent of process `pid` (field 4 of /proc/PID/stat), or -1.
pid_t parent_of(const std::string& pid) {
  std::ifstream in("/proc/" + pid + "/stat");
  std::string stat;
  std::getline(in, stat);
  const std::size_t close = stat.rfind(')');
  if (close == std::string::npos) return -1;
  std::istringstream rest(stat.substr(close + 2));
  char state = 0;
  pid_t parent = -1;
  rest >> state >> parent;
  return parent;
}

// Whether process `pid` still runs (not gone, not a zombie waiting for its parent).
bool running(pid_t pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
  std::string stat;
  if (!std::getline(in, stat)) return false;
  const std::size_t close = stat.rfind(')');
  return close != std::string::npos && close + 2 < stat.size() && stat[close + 2] != 'Z' &&
         stat[close + 2] != 'X';
}

// The process of `rank` among mpirun's children (Open MPI gives each rank
// OMPI_COMM_WORLD_RANK in its environment), or 0.
pid_t rank_process(pid_t mpirun, int rank) {
  const std::string wanted = std::string(1, '\0') + "OMPI_COMM_WORLD_RANK=" + std::to_string(rank);
  for (const fs::directory_entry& e : fs::directory_iterator("/proc")) {
    const std::string pid = e.path().filename().string();
    if (pid.find_first_not_of("0123456789") != std::string::npos) continue;
    if (parent_of(pid) != mpirun) continue;
    std::ifstream in(e.path() / "environ", std::ios::binary);
    const std::string env =
        std::string(1, '\0') + std::string(std::istreambuf_iterator<char>(in), {}) + '\0';
    if (env.find(wanted + '\0') != std::string::npos) return static_cast<pid_t>(std::stol(pid));
  }
  return 0;
}

// How many complete frames results.h5 has (SWMR reader: the run is still writing), or -1.
long frames_written(const fs::path& out) {
  if (!fs::exists(out / "results.h5")) return -1;
  const hid_t f =
      H5Fopen((out / "results.h5").c_str(), H5F_ACC_RDONLY | H5F_ACC_SWMR_READ, H5P_DEFAULT);
  if (f < 0) return -1;
  long n = -1;
  const hid_t d = H5Dopen2(f, "/frames/time", H5P_DEFAULT);
  if (d >= 0) {
    const hid_t s = H5Dget_space(d);
    n = static_cast<long>(H5Sget_simple_extent_npoints(s));
    H5Sclose(s);
    H5Dclose(d);
  }
  H5Fclose(f);
  return n;
}

// results.h5's `complete` attribute (1 only after a finished run closed it), or -1.
int complete_mark(const fs::path& out) {
  const hid_t f =
      H5Fopen((out / "results.h5").c_str(), H5F_ACC_RDONLY | H5F_ACC_SWMR_READ, H5P_DEFAULT);
  if (f < 0) return -1;
  int complete = -1;
  const hid_t a = H5Aopen(f, "complete", H5P_DEFAULT);
  if (a >= 0) {
    H5Aread(a, H5T_NATIVE_INT, &complete);
    H5Aclose(a);
  }
  H5Fclose(f);
  return complete;
}

class DistributedRunFailure : public ::testing::TestWithParam<int> {};

TEST_P(DistributedRunFailure, ARankKilledStopsEveryRankWithAMessage) {
  const int victim = GetParam();
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);  // (a file being written may refuse a reader)
  fs::create_directories(tmp_dir());
  // (files of its own: ctest runs the two cases side by side)
  const fs::path scene = tmp_dir() / ("long_bar_" + std::to_string(victim) + ".toml");
  std::ofstream(scene) << kLongBar;
  const fs::path out = tmp_dir() / ("killed_rank_" + std::to_string(victim));
  const fs::path log = tmp_dir() / ("killed_rank_" + std::to_string(victim) + ".log");
  fs::remove_all(out);
  std::vector<std::string> args = {FEMDEM_MPIEXEC,
                                   "-np",
                                   "2",
                                   "--oversubscribe",
                                   "--allow-run-as-root",
                                   "-x",
                                   "OMP_NUM_THREADS=1",
                                   "-x",
                                   "ASAN_OPTIONS=detect_leaks=0",
                                   FEMDEM_EXE,
                                   "run",
                                   scene.string(),
                                   "--quiet",
                                   "--threads",
                                   "1",
                                   "--out",
                                   out.string()};
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t files;
  posix_spawn_file_actions_init(&files);
  posix_spawn_file_actions_addopen(&files, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&files, 1, 2);
  pid_t mpirun = 0;
  ASSERT_EQ(posix_spawn(&mpirun, FEMDEM_MPIEXEC, &files, nullptr, argv.data(), environ), 0);
  posix_spawn_file_actions_destroy(&files);
  // running: both ranks up and a few frames written
  const auto give_up = Clock::now() + std::chrono::seconds(120);
  pid_t target = 0, other = 0;
  while (Clock::now() < give_up) {
    if (waitpid(mpirun, nullptr, WNOHANG) == mpirun) FAIL() << "the run ended before it was killed";
    target = rank_process(mpirun, victim);
    other = rank_process(mpirun, 1 - victim);
    if (target > 0 && other > 0 && frames_written(out) >= 3) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  ASSERT_GT(target, 0) << read_text(log);
  ASSERT_GE(frames_written(out), 3) << read_text(log);
  ASSERT_EQ(kill(target, SIGKILL), 0);
  // every rank stops, without waiting for the dead one: mpirun ends within a minute
  const auto killed = Clock::now();
  int status = 0;
  bool ended = false;
  while (Clock::now() < killed + std::chrono::seconds(60)) {
    if (waitpid(mpirun, &status, WNOHANG) == mpirun) {
      ended = true;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  if (!ended) {
    kill(other, SIGKILL);
    kill(mpirun, SIGKILL);
    waitpid(mpirun, &status, 0);
  }
  ASSERT_TRUE(ended) << "a rank still waits a minute after rank " << victim << " died\n"
                     << read_text(log);
  const double seconds = std::chrono::duration<double>(Clock::now() - killed).count();
  EXPECT_LT(seconds, 30.0);
  EXPECT_FALSE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << read_text(log);
  // (a rank mpirun killed may still be giving back its memory as mpirun ends: a large one
  // under the sanitizers takes a moment)
  const auto ended_at = Clock::now();
  while (running(other) && Clock::now() < ended_at + std::chrono::seconds(10))
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  EXPECT_FALSE(running(other)) << "rank " << 1 - victim << " outlived mpirun by 10 s";
  std::printf("mpirun ended %.2f s after rank %d was killed\n", seconds, victim);
  // the message names the rank and what happened to it (Open MPI's own)
  const std::string said = read_text(log);
  EXPECT_NE(said.find("rank " + std::to_string(victim)), std::string::npos) << said;
  EXPECT_NE(said.find("signal 9"), std::string::npos) << said;
  // what was written stays readable; nothing says the run is complete
  EXPECT_GE(frames_written(out), 3);
  EXPECT_EQ(complete_mark(out), 0);
  if (fs::exists(out / "summary.json")) {
    EXPECT_NE(nlohmann::json::parse(read_text(out / "summary.json")).value("status", ""),
              "completed");
  }
}

INSTANTIATE_TEST_SUITE_P(Ranks, DistributedRunFailure, ::testing::Values(0, 1));

}  // namespace
}  // namespace femdem::test
