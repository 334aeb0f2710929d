// rt2cpr_mpi under Debian's mpirun: 1, 2 and 3 ranks give the single
// process's image bits for any tile size, over passes and frames; only rank 0 prints; and
// every way a job can fail (a bad command line, a missing scene, a scene one rank cannot
// read, a rank out of memory, a rank killed mid-render) ends it with one line from rank 0,
// a non-zero status and no output file.
//
// mpirun runs as root only with --allow-run-as-root, on fewer cores than ranks x threads only
// with --oversubscribe (3 ranks of 2 threads), and --bind-to none keeps it from pinning each
// rank to one core. -q leaves out mpirun's own report of a failing job, so that stderr holds
// rank 0's line alone.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "rt2/image/image_io.h"
#include "tests/rt2/io/animated_gltf.h"
#include "tests/rt2cpr/cli_fixture.h"

namespace rt2::test {
namespace {

constexpr const char* kMpirun =
    "mpirun -q --allow-run-as-root --oversubscribe --bind-to none";
const std::string kGlass = std::string(RT2_SOURCE_DIR) + "/scenes/glass.toml";

// 64 x 48 pixels of 4 samples in 3 passes (uneven: 1, 1, 2 samples), two threads a rank.
constexpr const char* kSmall = "--width 64 --height 48 --subpixels 4 --passes 3 --threads 2";

std::string mpirun(int ranks, const std::string& args) {
  return std::string(kMpirun) + " -np " + std::to_string(ranks) + " " + RT2CPR_MPI_BIN + " " +
         args;
}

int count(const std::string& text, const std::string& what) {
  int n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

class Mpi : public Cli {
 protected:
  // A failure: `status`, one line on stderr (rank 0's) holding `needle`, no file but the
  // captured streams and `keep` in the test folder.
  void expect_one_line_failure(const Outcome& r, int status, const std::string& needle,
                               std::size_t keep = 0) const {
    EXPECT_EQ(r.status, status) << r.err;
    expect_clean_failure(r, needle);
    EXPECT_EQ(files_other_than_streams(), keep);
  }
};

// ---- the same image ------------------------------------------------------------------------

struct Case {
  const char* name;
  std::string scene;  // empty: the built-in scene
  int ranks;
  int tile;           // 0: bands of rows
  int frames;         // > 1: with the lights moving (--animate-lights)
  // false: rank 0 only hands tiles out (--rank0 serve), so that every tile is surely
  // rendered on another rank and sent; when it renders too, how many tiles each rank gets
  // depends on timing.
  bool rank0_renders = true;
};

void PrintTo(const Case& c, std::ostream* os) { *os << c.name; }

class SameImage : public Mpi, public ::testing::WithParamInterface<Case> {};

TEST_P(SameImage, AsOneProcessBitForBit) {
  const Case& c = GetParam();
  const std::string args = std::string(kSmall) + " --tile " + std::to_string(c.tile) +
                           " --frames " + std::to_string(c.frames) +
                           (c.frames > 1 ? " --animate-lights" : "") +
                           (c.scene.empty() ? "" : " --scene " + c.scene);
  const Outcome one = run(args + " --quiet --output " + path("one.exr") + " --stats " +
                          path("one.json"));
  ASSERT_EQ(one.status, 0) << one.err;
  const Outcome job = run_command(mpirun(c.ranks, args + (c.rank0_renders ? "" : " --rank0 serve") +
                                                      " --output " + path("job.exr") +
                                                      " --stats " + path("job.json")));
  ASSERT_EQ(job.status, 0) << job.err;
  EXPECT_EQ(job.err, "");
  // Only rank 0 prints: its report once, each file written once.
  EXPECT_EQ(count(job.out, "fps median"), 1) << job.out;
  EXPECT_EQ(count(job.out, "wrote "), 2) << job.out;

  const Image a = read_image(path("one.exr")), b = read_image(path("job.exr"));
  ASSERT_EQ(a.width, b.width);
  ASSERT_EQ(a.height, b.height);
  ASSERT_EQ(a.rgb.size(), b.rgb.size());
  for (std::size_t i = 0; i < a.rgb.size(); i += 3)
    ASSERT_EQ(std::memcmp(&a.rgb[i], &b.rgb[i], 3 * sizeof(float)), 0)
        << "pixel " << i / 3 % 64 << "," << i / 3 / 64;

  // The statistics: the rays of one process, every rank's figures, every tile once.
  const auto stats = [&](const char* name) {
    return nlohmann::json::parse(std::ifstream(path(name)));
  };
  const nlohmann::json js = stats("job.json"), os = stats("one.json");
  EXPECT_EQ(js["rays_total"], os["rays_total"]);
  ASSERT_EQ(js["mpi_processes"], c.ranks);
  ASSERT_EQ(js["mpi_ranks"].size(), std::size_t(c.ranks));
  std::uint64_t tiles = 0;
  for (const auto& r : js["mpi_ranks"]) {
    const bool serves_only = r["rank"] == 0 && !c.rank0_renders;
    EXPECT_EQ(r["threads"], serves_only ? 0 : 2);
    const auto rendered = r["tiles"].get<std::uint64_t>();
    tiles += rendered;
    EXPECT_EQ(r["busy_ms"].get<double>() > 0.0, rendered > 0) << r;
    if (serves_only) {
      EXPECT_EQ(rendered, 0u);
    }
    // A worker sends one request a frame (4 bytes), then each tile's index and pixels.
    const auto sent = r["bytes_sent"].get<std::uint64_t>();
    if (r["rank"] != 0) {
      EXPECT_EQ(sent > 4u * std::uint64_t(c.frames), rendered > 0) << r;
    }
  }
  const int threads = 2 * (c.ranks - !c.rank0_renders);
  const auto across = [&](int pixels) { return std::uint64_t((pixels + c.tile - 1) / c.tile); };
  const std::uint64_t per_frame = c.tile > 0 ? across(64) * across(48)
                                             : std::uint64_t(std::min(48, threads * 4));  // x grain
  EXPECT_EQ(tiles, per_frame * std::uint64_t(c.frames));
}

INSTANTIATE_TEST_SUITE_P(
    Mpi, SameImage,
    ::testing::Values(Case{"builtin_1_rank_tile_16", "", 1, 16, 1},
                      Case{"builtin_2_ranks_tile_7", "", 2, 7, 1},
                      Case{"builtin_2_ranks_rank0_serves_tile_16", "", 2, 16, 1, false},
                      Case{"builtin_3_ranks_rank0_serves_bands", "", 3, 0, 1, false},
                      Case{"builtin_3_ranks_tile_16_two_frames_moving_lights", "", 3, 16, 2},
                      Case{"glass_2_ranks_rank0_serves_tile_5", kGlass, 2, 5, 1, false},
                      Case{"glass_3_ranks_tile_16", kGlass, 3, 16, 1}),
    [](const ::testing::TestParamInfo<Case>& p) { return std::string(p.param.name); });

TEST_F(Mpi, AnAnimatedSceneIsPosedByEveryRankFrameByFrameAsOneProcess) {
  write("a.gltf", rt2::test::animated_gltf());
  const std::string args = path("a.gltf") + " " + kSmall + " --tile 16 --frames 3 --fps 2";
  ASSERT_EQ(run(args + " --quiet --output " + path("one_#.exr")).status, 0);
  const Outcome job = run_command(mpirun(2, args + " --output " + path("job_#.exr")));
  ASSERT_EQ(job.status, 0) << job.err;
  EXPECT_EQ(count(job.out, "wrote 3 frames"), 1) << job.out;
  for (const char* f : {"1", "2", "3"}) {
    const Image a = read_image(path(std::string("one_") + f + ".exr")),
                b = read_image(path(std::string("job_") + f + ".exr"));
    ASSERT_EQ(a.rgb.size(), b.rgb.size());
    EXPECT_EQ(std::memcmp(a.rgb.data(), b.rgb.data(), a.rgb.size() * sizeof(float)), 0) << f;
  }
}

// ---- input errors: one line, from rank 0 ---------------------------------------------------

TEST_F(Mpi, ABadCommandLineIsReportedOnce) {
  expect_one_line_failure(run_command(mpirun(3, "--bogus")), 2, "--bogus");
  expect_one_line_failure(run_command(mpirun(3, "--interactive")), 2, "--interactive");
  expect_one_line_failure(run_command(mpirun(1, "--rank0 serve")), 2, "2 processes or more");
  expect_one_line_failure(run("--rank0 serve"), 2, "rt2cpr_mpi");  // not one process's
}

TEST_F(Mpi, AMissingSceneIsReportedOnce) {
  const Outcome r = run_command(mpirun(3, std::string(kSmall) + " --scene " + path("none.toml") +
                                              " --output " + path("x.png")));
  expect_one_line_failure(r, 1, "none.toml");
  EXPECT_EQ(r.err.find("rank "), std::string::npos) << "every rank fails alike: " << r.err;
}

TEST_F(Mpi, HelpIsPrintedOnce) {
  const Outcome r = run_command(mpirun(3, "--help"));
  EXPECT_EQ(r.status, 0);
  EXPECT_EQ(count(r.out, "--scene"), count(run("--help").out, "--scene"));
}

// ---- a rank that fails ---------------------------------------------------------------------

// A scene on rank 0's disk and not on the others' (each rank starts in its own folder, as on
// machines that do not share one): rank 1, the first that fails, is named; nothing renders.
TEST_F(Mpi, ARankThatCannotReadTheSceneStopsTheJob) {
  dir_.write("root/glass.toml", slurp(kGlass));
  std::filesystem::create_directories(path("others"));
  const std::string args = std::string(kSmall) + " glass.toml --output " + path("x.png");
  const Outcome r = run_command(std::string(kMpirun) + " -np 1 --wdir " + path("root") + " " +
                                RT2CPR_MPI_BIN + " " + args + " : -np 2 --wdir " +
                                path("others") + " " + RT2CPR_MPI_BIN + " " + args);
  expect_one_line_failure(r, 1, "rank 1 (", 2);  // the two folders
  EXPECT_NE(r.err.find("glass.toml"), std::string::npos) << r.err;
  EXPECT_EQ(r.out, "");
}

// Ranks 1 and 2 run out of memory as they allocate their film: their data segment is capped
// at 200 MB (prlimit), which MPI and the scene fit in, and the film of 3000 x 3000 pixels
// takes 324 MB. Rank 1 is named; nothing renders. (Under AddressSanitizer a capped process
// cannot even start, its shadow memory counting as data, and a failed allocation ends it
// instead of throwing: release builds only.)
TEST_F(Mpi, ARankOutOfMemoryStopsTheJob) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "AddressSanitizer cannot run under a data segment cap";
#endif
  const std::string args = "--width 3000 --height 3000 --depth 0 --output " + path("x.png");
  const Outcome r = run_command(std::string(kMpirun) + " -np 1 " + RT2CPR_MPI_BIN + " " + args +
                                " : -np 2 prlimit --data=" + std::to_string(200 << 20) + " " +
                                RT2CPR_MPI_BIN + " " + args);
  expect_one_line_failure(r, 1, "rank 1 (");
  EXPECT_NE(r.err.find("out of memory"), std::string::npos) << r.err;
}

// A job mpirun starts in the background: its pid and exit status.
class Background {
 public:
  // `command` is exec'd by sh (a program and its arguments, redirections): its pid is the
  // program's.
  explicit Background(const std::string& command) {
    pid_ = ::fork();
    if (pid_ == 0) {
      ::execl("/bin/sh", "sh", "-c", ("exec " + command).c_str(), static_cast<char*>(nullptr));
      ::_exit(127);
    }
  }
  ~Background() {
    if (pid_ > 0 && !waited_) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
    }
  }
  pid_t pid() const { return pid_; }
  int wait() {
    int raw = 0;
    ::waitpid(pid_, &raw, 0);
    waited_ = true;
    return WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  }

 private:
  pid_t pid_ = -1;
  bool waited_ = false;
};

// The process mpirun `parent` started as rank `rank` (its OMPI_COMM_WORLD_RANK), or -1.
pid_t rank_pid(pid_t parent, int rank) {
  for (const auto& e : std::filesystem::directory_iterator("/proc")) {
    const std::string name = e.path().filename().string();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    std::ifstream stat(e.path() / "stat");
    std::string line;
    std::getline(stat, line);
    const std::size_t close = line.rfind(')');
    if (close == std::string::npos) continue;
    char state = 0;
    int ppid = 0;
    if (std::sscanf(line.c_str() + close + 1, " %c %d", &state, &ppid) != 2 || ppid != parent)
      continue;
    std::ifstream env(e.path() / "environ", std::ios::binary);
    for (std::string var; std::getline(env, var, '\0');)
      if (var == "OMPI_COMM_WORLD_RANK=" + std::to_string(rank)) return std::stoi(name);
  }
  return -1;
}

// SIGKILL to rank 1 while the ranks render (a crash or the OOM killer look the same to
// mpirun): mpirun ends the job, rank 0 says so in one line, and no image is written.
TEST_F(Mpi, ARankKilledMidRenderEndsTheJobWithOneLine) {
  Background job("env " + std::string(kChildEnv) + mpirun(3, std::string(kSmall) +
                                                        " --frames 1000000 --output " +
                                                        path("x.png")) +
                 " >" + path("stdout") + " 2>" + path("stderr"));
  ASSERT_GT(job.pid(), 0);
  // Once rank 0 has printed the first frame's line, every rank renders the second. A guard
  // against a hang, not a measurement: the line comes in about a second.
  const auto guard = std::chrono::steady_clock::now() + std::chrono::minutes(2);
  while (slurp(path("stdout")).find("frame 1:") == std::string::npos) {
    ASSERT_LT(std::chrono::steady_clock::now(), guard) << "the job did not start";
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  const pid_t victim = rank_pid(job.pid(), 1);
  ASSERT_GT(victim, 0);
  ASSERT_EQ(::kill(victim, SIGKILL), 0);
  const int status = job.wait();
  const Outcome r{status, slurp(path("stdout")), slurp(path("stderr"))};
  EXPECT_NE(r.status, 0);
  expect_clean_failure(r, "ended by mpirun");
  EXPECT_EQ(files_other_than_streams(), 0u);
}

}  // namespace
}  // namespace rt2::test
