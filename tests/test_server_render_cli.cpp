// gearsph render / gearsph plot on a finished run: the pictures the service
// draws, from the command line.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <sys/wait.h>
#include <unistd.h>

namespace {

namespace fs = std::filesystem;

int gearsph(const std::string& args) {
  const std::string cmd = std::string(GEARSPH_BINARY) + " " + args + " >/dev/null 2>&1";
  const int status = std::system(cmd.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

bool is_png(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  char sig[8] = {};
  f.read(sig, 8);
  return f && std::string(sig + 1, 3) == "PNG" && fs::file_size(p) > 1000;
}

class RenderCli : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = fs::temp_directory_path() / ("gearsph-render-cli-" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    std::ofstream(dir_ / "job.json") << R"({"name": "render-cli",
      "scene": {"type": "plate", "length_m": 0.1, "thickness_m": 0.01},
      "discretization": {"spacing_m": 0.002}, "time": {"end_s": 0.002},
      "output": {"frames": 3}})";
    ASSERT_EQ(gearsph("run " + (dir_ / "job.json").string() + " --out " + (dir_ / "run").string() +
                      " --threads 1 --quiet"),
              0);
  }
  static void TearDownTestSuite() { fs::remove_all(dir_); }
  static fs::path dir_;
};
fs::path RenderCli::dir_;

TEST_F(RenderCli, RendersOneFrameFromTheRunOrItsResultsFile) {
  const fs::path run = dir_ / "run";
  EXPECT_EQ(gearsph("render " + run.string() + " --out " + (dir_ / "last.png").string()), 0);
  EXPECT_TRUE(is_png(dir_ / "last.png"));
  EXPECT_EQ(gearsph("render " + (run / "results.h5").string() + " --field pressure --frame 0" +
                    " --zoom=0,-0.01,0.05,0.01 --out " + (dir_ / "first.png").string()),
            0);
  EXPECT_TRUE(is_png(dir_ / "first.png"));
  EXPECT_EQ(gearsph("render " + run.string() + " --field max_principal --range=-1e6,2e6 --out " +
                    (dir_ / "sigma1.png").string()),
            0);
  EXPECT_TRUE(is_png(dir_ / "sigma1.png"));
}

TEST_F(RenderCli, FramesAllWritesEverySnapshot) {
  const fs::path out = dir_ / "frames";
  ASSERT_EQ(gearsph("render " + (dir_ / "run").string() + " --frames all --out " + out.string()),
            0);
  int pngs = 0;
  for (const auto& e : fs::directory_iterator(out)) pngs += is_png(e.path()) ? 1 : 0;
  EXPECT_EQ(pngs, 4);  // the initial state and three snapshots
  EXPECT_TRUE(fs::exists(out / "von_mises_0003.png"));
}

TEST_F(RenderCli, PlotsHistoryColumns) {
  EXPECT_EQ(gearsph("plot " + (dir_ / "run").string() + " --columns tip_y_m,tip_vy_m_s --out " +
                    (dir_ / "plot.png").string()),
            0);
  EXPECT_TRUE(is_png(dir_ / "plot.png"));
}

TEST_F(RenderCli, RefusesWhatItCannotDraw) {
  const std::string run = (dir_ / "run").string(), out = (dir_ / "bad.png").string();
  EXPECT_EQ(gearsph("render " + run + " --field no_such_field --out " + out), 2);
  EXPECT_EQ(gearsph("render " + run + " --frame 99 --out " + out), 2);
  EXPECT_EQ(gearsph("plot " + run + " --columns no_such_column --out " + out), 2);
  EXPECT_EQ(gearsph("render " + run), 2);  // no --out
  // A usage error (2), as the HTTP route answers 400, not a failed render (1).
  EXPECT_EQ(gearsph("render " + run + " --zoom 0.05,0,0,0.01 --out " + out), 2);
  EXPECT_EQ(gearsph("render " + run + " --zoom 0,0,x,0.01 --out " + out), 2);
  EXPECT_EQ(gearsph("render " + run + " --range 5,1 --out " + out), 2);
  EXPECT_EQ(gearsph("render " + run + " --range a,b --out " + out), 2);
  EXPECT_EQ(gearsph("render " + run + " --field body --range 0,1 --out " + out), 2);
  // Another file beside results.h5 is not silently replaced by it.
  EXPECT_EQ(gearsph("render " + run + "/other.h5 --out " + out), 2);
  EXPECT_FALSE(fs::exists(dir_ / "bad.png"));
}

}  // namespace
