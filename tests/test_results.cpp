// results.h5 and results.xmf: a real run through execute_job read back with
// ResultsFile and checked against the simulation state it came from, the
// XDMF sidecar against the file it points into, the reader's refusals, and
// `gearsph run` killed with SIGKILL at random moments (results_writer.hpp).
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <random>
#include <regex>
#include <set>
#include <sstream>
#include <string_view>
#include <thread>

#include "results/h5_series.hpp"
#include "results/h5_util.hpp"
#include "results/outlines.hpp"
#include "results/register_outputs.hpp"
#include "results/results_layout.hpp"
#include "results/results_reader.hpp"
#include "results/results_writer.hpp"
#include "results/xdmf_writer.hpp"
#include "solver/job/job.hpp"
#include "solver/run/execute.hpp"

extern char** environ;

namespace gearsph::results {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

fs::path fresh_dir(const std::string& name) {
  const fs::path dir =
      fs::temp_directory_path() / ("gearsph_results_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// ---------------------------------------------------------------------------
// A minimal XML reader: enough to prove results.xmf well-formed (matching
// tags, quoted attributes, known entities) and to walk it.

struct XmlNode {
  std::string name;
  std::map<std::string, std::string> attrs;
  std::string text;
  std::vector<XmlNode> children;
  const XmlNode& child(const std::string& n) const {
    for (const XmlNode& c : children) {
      if (c.name == n) return c;
    }
    throw std::runtime_error("no <" + n + "> in <" + name + ">");
  }
};

class XmlReader {
 public:
  explicit XmlReader(std::string text) : s_(std::move(text)) {}

  XmlNode document() {
    skip_misc();
    XmlNode root = element();
    skip_misc();
    if (at_ != s_.size()) fail("content after the root element");
    return root;
  }

 private:
  [[noreturn]] void fail(const std::string& why) const {
    throw std::runtime_error("XML: " + why + " at offset " + std::to_string(at_));
  }
  bool starts(const char* p) const { return s_.compare(at_, std::strlen(p), p) == 0; }
  void skip_space() {
    while (at_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[at_]))) ++at_;
  }
  void skip_past(const char* end) {
    const auto e = s_.find(end, at_);
    if (e == std::string::npos) fail(std::string("missing ") + end);
    at_ = e + std::strlen(end);
  }
  // Declarations, comments and a DOCTYPE (with an internal subset).
  void skip_misc() {
    for (skip_space(); at_ < s_.size(); skip_space()) {
      if (starts("<?")) {
        skip_past("?>");
      } else if (starts("<!--")) {
        skip_past("-->");
      } else if (starts("<!DOCTYPE")) {
        const auto bracket = s_.find('[', at_), close = s_.find('>', at_);
        if (bracket != std::string::npos && bracket < close) skip_past("]");
        skip_past(">");
      } else {
        return;
      }
    }
  }
  std::string name() {
    const std::size_t start = at_;
    while (at_ < s_.size() &&
           (std::isalnum(static_cast<unsigned char>(s_[at_])) || s_[at_] == '_' || s_[at_] == ':' ||
            s_[at_] == '-' || s_[at_] == '.')) {
      ++at_;
    }
    if (at_ == start) fail("expected a name");
    return s_.substr(start, at_ - start);
  }
  std::string decode(const std::string& raw) const {
    static const std::map<std::string, char> kEntities = {
        {"lt", '<'}, {"gt", '>'}, {"amp", '&'}, {"quot", '"'}, {"apos", '\''}};
    std::string out;
    for (std::size_t i = 0; i < raw.size(); ++i) {
      if (raw[i] == '<') throw std::runtime_error("XML: '<' in text or attribute");
      if (raw[i] != '&') {
        out += raw[i];
        continue;
      }
      const auto semi = raw.find(';', i);
      const auto it = semi == std::string::npos ? kEntities.end()
                                                : kEntities.find(raw.substr(i + 1, semi - i - 1));
      if (it == kEntities.end()) throw std::runtime_error("XML: unknown entity");
      out += it->second;
      i = semi;
    }
    return out;
  }
  XmlNode element() {
    if (!starts("<")) fail("expected an element");
    ++at_;
    XmlNode node;
    node.name = name();
    for (skip_space(); !starts("/>") && !starts(">"); skip_space()) {
      const std::string key = name();
      skip_space();
      if (!starts("=")) fail("expected = after " + key);
      ++at_;
      skip_space();
      const char quote = at_ < s_.size() ? s_[at_] : '\0';
      if (quote != '"' && quote != '\'') fail("unquoted attribute " + key);
      const auto end = s_.find(quote, ++at_);
      if (end == std::string::npos) fail("unterminated attribute " + key);
      if (!node.attrs.emplace(key, decode(s_.substr(at_, end - at_))).second)
        fail("duplicate " + key);
      at_ = end + 1;
    }
    if (starts("/>")) {
      at_ += 2;
      return node;
    }
    ++at_;
    content(node);
    return node;
  }
  void content(XmlNode& node) {
    for (;;) {
      const auto lt = s_.find('<', at_);
      if (lt == std::string::npos) fail("unclosed <" + node.name + ">");
      node.text += decode(s_.substr(at_, lt - at_));
      at_ = lt;
      if (starts("<!--")) {
        skip_past("-->");
      } else if (starts("</")) {
        at_ += 2;
        if (name() != node.name) fail("mismatched </...> for <" + node.name + ">");
        skip_space();
        if (!starts(">")) fail("expected >");
        ++at_;
        return;
      } else {
        node.children.push_back(element());
      }
    }
  }

  std::string s_;
  std::size_t at_ = 0;
};

std::vector<double> numbers(const std::string& text) {
  std::istringstream in(text);
  std::vector<double> out;
  for (double v; in >> v;) out.push_back(v);
  return out;
}

// ---------------------------------------------------------------------------
// One real run, shared by the ResultsRun tests.

const json kPlateJob = json::parse(R"({
  "scene": {"type": "plate", "length_m": 0.1, "thickness_m": 0.01},
  "discretization": {"spacing_m": 0.002},
  "time": {"end_s": 0.01},
  "output": {"frames": 10}})");

// The particle state the simulation had at each snapshot.
struct Captured {
  double time = 0.0;
  std::int64_t step = 0;
  Particles particles;
};

// Also opens results.h5 while the run writes it, as the job service does
// from another thread of the same process: before the writer adds frame k,
// a reader sees frames 0..k-1 (the file appears with the first sample).
class SnapshotRecorder : public RunObserver {
 public:
  explicit SnapshotRecorder(fs::path results) : results_(std::move(results)) {}
  void on_snapshot(const Simulation& sim, std::int64_t frame) override {
    states.push_back({sim.time, sim.step, sim.particles});
    const ResultsFile live(results_);
    live_counts.push_back(live.frame_count());
    if (frame == 0) return;
    const std::size_t last = live.frame_count() - 1;
    const Frame f = live.frame(last);
    live_last_ok.push_back(f.time_s == states[last].time &&
                           f.position[0] == states[last].particles.x[0]);
  }
  std::vector<Captured> states;
  std::vector<std::size_t> live_counts;
  std::vector<bool> live_last_ok;

 private:
  fs::path results_;
};

class ResultsRun : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    register_outputs();
    dir_ = fresh_dir("run");
    PreparedJob prepared = prepare_job(kPlateJob, 1);
    planned_frames_ = prepared.frames;
    estimate_ = estimate_results_bytes(prepared);
    recorder_ = std::make_unique<SnapshotRecorder>(dir_ / kResultsFile);
    ExecuteOptions options;
    options.threads = 1;
    options.observer = recorder_.get();
    execution_ = execute_job(kPlateJob, dir_, options);
  }
  static void TearDownTestSuite() {
    recorder_.reset();
    fs::remove_all(dir_);
  }
  static const Captured& state(std::size_t frame) { return recorder_->states.at(frame); }

  static inline fs::path dir_;
  static inline std::int64_t planned_frames_ = 0;
  static inline std::uint64_t estimate_ = 0;
  static inline std::unique_ptr<SnapshotRecorder> recorder_;
  static inline Execution execution_;
};

TEST_F(ResultsRun, FileOpensWithEveryPlannedFrame) {
  ASSERT_EQ(execution_.run.status, "completed");
  const ResultsFile file(dir_ / kResultsFile);
  EXPECT_GE(planned_frames_, 10);
  EXPECT_EQ(file.frame_count(), static_cast<std::size_t>(planned_frames_));
  EXPECT_EQ(recorder_->states.size(), file.frame_count());
  EXPECT_EQ(file.particle_count(), state(0).particles.n);
  EXPECT_EQ(file.status(), "completed");
  EXPECT_EQ(file.steps_done(), execution_.run.steps_done);
  for (std::size_t k = 0; k < file.frame_count(); ++k) {
    EXPECT_EQ(file.frame_times()[k], state(k).time);
    EXPECT_EQ(file.frame_steps()[k], state(k).step);
  }
  const std::set<std::string> files(execution_.files.begin(), execution_.files.end());
  EXPECT_TRUE(files.count("results.h5"));
  EXPECT_TRUE(files.count("results.xmf"));
  EXPECT_FALSE(fs::exists(dir_ / "results.h5.tmp"));
  EXPECT_FALSE(fs::exists(dir_ / "results.xmf.tmp"));
}

TEST_F(ResultsRun, ReaderSeesCommittedFramesWhileTheRunWrites) {
  const std::vector<std::size_t>& counts = recorder_->live_counts;
  ASSERT_EQ(counts.size(), recorder_->states.size());
  for (std::size_t k = 0; k < counts.size(); ++k) EXPECT_EQ(counts[k], k) << "snapshot " << k;
  for (std::size_t k = 0; k < recorder_->live_last_ok.size(); ++k) {
    EXPECT_TRUE(recorder_->live_last_ok[k]) << "frame " << k;
  }
}

TEST_F(ResultsRun, FirstFrameIsTheInitialConfiguration) {
  const ResultsFile file(dir_ / kResultsFile);
  const Frame f = file.frame(0);
  const InitialState init = file.initial();
  const Particles& p = state(0).particles;
  EXPECT_EQ(f.step, 0);
  EXPECT_EQ(f.time_s, 0.0);
  EXPECT_EQ(f.position, init.position);
  EXPECT_EQ(f.body_id, init.body_id);
  EXPECT_EQ(f.particle_id, init.particle_id);
  for (std::size_t i = 0; i < p.n; ++i) {
    EXPECT_EQ(init.position[3 * i], p.x0[i]);
    EXPECT_EQ(init.position[3 * i + 1], p.y0[i]);
    EXPECT_EQ(init.position[3 * i + 2], 0.0);
    EXPECT_EQ(init.mass[i], p.mass[i]);
    EXPECT_EQ(init.particle_id[i], static_cast<std::int32_t>(i));
    for (int c = 0; c < 3; ++c) EXPECT_EQ(f.displacement[3 * i + c], 0.0);
    EXPECT_EQ(f.velocity[3 * i + 1], p.vy[i]);  // the plate starts in its bending mode
  }
}

TEST_F(ResultsRun, LaterFrameHoldsWhatTheSimulationHad) {
  const ResultsFile file(dir_ / kResultsFile);
  const std::size_t k = file.frame_count() / 2;
  const Frame f = file.frame(k);
  const Captured& s = state(k);
  const Particles& p = s.particles;
  ASSERT_EQ(f.position.size(), 3 * p.n);
  EXPECT_EQ(f.time_s, s.time);
  EXPECT_EQ(f.step, s.step);
  EXPECT_GT(f.step, 0);
  double moved = 0.0;
  for (std::size_t i = 0; i < p.n; ++i) {
    EXPECT_EQ(f.position[3 * i], p.x[i]);
    EXPECT_EQ(f.position[3 * i + 1], p.y[i]);
    EXPECT_EQ(f.velocity[3 * i], p.vx[i]);
    EXPECT_EQ(f.velocity[3 * i + 1], p.vy[i]);
    EXPECT_EQ(f.displacement[3 * i], p.x[i] - p.x0[i]);
    EXPECT_EQ(f.displacement[3 * i + 1], p.y[i] - p.y0[i]);
    EXPECT_EQ(f.stress_xx[i], -p.p[i] + p.sxx[i]);
    EXPECT_EQ(f.stress_yy[i], -p.p[i] + p.syy[i]);
    EXPECT_EQ(f.stress_xy[i], p.sxy[i]);
    EXPECT_EQ(f.stress_zz[i], -p.p[i] + p.szz[i]);
    EXPECT_EQ(f.pressure[i], p.p[i]);
    EXPECT_EQ(f.von_mises[i], p.von_mises(i));
    EXPECT_EQ(f.density[i], p.rho[i]);
    EXPECT_EQ(f.body_id[i], p.body[i]);
    moved = std::max(moved, std::abs(f.displacement[3 * i + 1]));
  }
  EXPECT_GT(moved, 0.0);  // a frame of a moving plate, not a copy of frame 0
  // Spot check against the history's own record of the same instant.
  const std::vector<double> t = file.history("time_s");
  const std::vector<double> vm = file.history("max_von_mises_Pa");
  const auto row = std::find(t.begin(), t.end(), s.time);
  ASSERT_NE(row, t.end());
  EXPECT_EQ(*std::max_element(f.von_mises.begin(), f.von_mises.end()), vm[row - t.begin()]);
}

TEST_F(ResultsRun, HistoriesEqualHistoryCsv) {
  const ResultsFile file(dir_ / kResultsFile);
  std::istringstream csv(read_text(dir_ / "history.csv"));
  std::string line;
  std::getline(csv, line);
  std::vector<std::string> header;
  for (std::istringstream h(line); std::getline(h, line, ',');) header.push_back(line);
  EXPECT_EQ(file.history_columns(), header);
  EXPECT_EQ(file.history_columns().front(), "time_s");
  std::vector<std::vector<double>> columns;
  for (const std::string& c : header) columns.push_back(file.history(c));
  std::size_t row = 0;
  char text[32];
  for (std::string csv_line; std::getline(csv, csv_line); ++row) {
    std::istringstream cells(csv_line);
    std::string cell;
    for (std::size_t c = 0; std::getline(cells, cell, ','); ++c) {
      ASSERT_LT(row, columns[c].size());
      std::snprintf(text, sizeof text, "%.10g", columns[c][row]);  // history.csv's precision
      ASSERT_EQ(cell, text) << header[c] << " row " << row;
    }
  }
  EXPECT_EQ(row, file.history_rows());
  EXPECT_EQ(row, execution_.run.history.rows());
  for (std::size_t c = 0; c < header.size(); ++c) {
    EXPECT_EQ(columns[c], execution_.run.history.column(header[c])) << header[c];
  }
}

TEST_F(ResultsRun, MetaRoundTripsJobAndNamesUnits) {
  const ResultsFile file(dir_ / kResultsFile);
  EXPECT_EQ(file.job(), json::parse(read_text(dir_ / "job.json")));
  EXPECT_EQ(file.job().at("scene").at("type"), "plate");
  EXPECT_EQ(file.format_version(), kFormatVersion);
  EXPECT_EQ(file.solver_version(), kSolverVersion);
  EXPECT_TRUE(std::regex_match(file.created(), std::regex(R"(\d{4}-\d\d-\d\dT\d\d:\d\d:\d\dZ)")))
      << file.created();
  const json units = file.units();
  for (const FieldSpec& f : kFrameFields) {
    EXPECT_EQ(units.at(std::string("/frames/") + f.name), f.unit);
  }
  EXPECT_EQ(units.at("/frames/time"), "s");
  EXPECT_EQ(units.at("/initial/position"), "m");
  EXPECT_EQ(units.at("/bodies/E_Pa"), "Pa");
  EXPECT_EQ(units.at("/histories/time_s"), "s");
  EXPECT_EQ(units.at("/histories/max_von_mises_Pa"), "Pa");
  EXPECT_EQ(units.at("/histories/kinetic_J_per_m"), "J/m");
  for (const std::string& c : file.history_columns())
    EXPECT_TRUE(units.contains("/histories/" + c));
}

TEST_F(ResultsRun, BodiesDescribeTheScene) {
  const ResultsFile file(dir_ / kResultsFile);
  const std::vector<BodyInfo> bodies = file.bodies();
  ASSERT_EQ(bodies.size(), 1u);
  EXPECT_EQ(bodies[0].name, "plate");
  EXPECT_EQ(bodies[0].begin, 0);
  EXPECT_EQ(bodies[0].end, static_cast<std::int64_t>(file.particle_count()));
  const json material = file.job().at("scene").at("material");
  EXPECT_EQ(bodies[0].E_Pa, material.at("E_Pa").get<double>());
  EXPECT_EQ(bodies[0].nu, material.at("nu").get<double>());
  EXPECT_EQ(bodies[0].rho_kg_m3, material.at("rho_kg_m3").get<double>());
  EXPECT_TRUE(file.outlines().empty());
}

// Frame fields: one chunk per frame, written as they are by default
// (output.compress false: deflate took a quarter of a short run's time).
TEST_F(ResultsRun, FieldsAreChunkedOneFrameAChunkAndStoredRawByDefault) {
  h5::QuietErrors quiet;
  h5::Id f = h5::open_file_read(dir_ / kResultsFile);
  const std::size_t n = state(0).particles.n;
  for (const FieldSpec& spec : kFrameFields) {
    h5::Id set = h5::open_dataset(f.get(), std::string("frames/") + spec.name);
    EXPECT_FALSE(h5::has_deflate(set.get())) << spec.name;
    h5::Id dcpl(H5Dget_create_plist(set.get()), H5Pclose);
    hsize_t chunk[3] = {0, 0, 0};
    ASSERT_EQ(H5Pget_chunk(dcpl.get(), 3, chunk), spec.components == 3 ? 3 : 2);
    EXPECT_EQ(chunk[0], 1u);  // one frame per chunk
    EXPECT_EQ(chunk[1], n);
  }
  for (const char* name : {"initial/position", "initial/mass", "initial/body_id"}) {
    EXPECT_TRUE(h5::has_deflate(h5::open_dataset(f.get(), name).get())) << name;
  }
}

// A row written straight to its chunks (Series::append_row_direct) reads
// back as written, across chunks and into a last partial one, and past the
// planned rows.
TEST(ResultsSeries, RowsWrittenStraightToTheirChunksReadBackAsWritten) {
  h5::QuietErrors quiet;
  const fs::path dir = fresh_dir("direct_rows");
  const fs::path path = dir / "rows.h5";
  constexpr hsize_t kAlong = 10, kPerChunk = 4;  // chunks of 4, 4 and 2 (padded)
  std::vector<std::vector<double>> rows;
  {
    h5::Id file = h5::create_file(path);
    h5::Series::Shape shape;
    shape.row = {kAlong, 3};
    shape.chunk = {1, kPerChunk, 3};
    const double fill = std::numeric_limits<double>::quiet_NaN();
    h5::Series series(file.get(), "vectors", H5T_IEEE_F64LE, shape, 2, &fill);
    for (int r = 0; r < 3; ++r) {  // the third row grows the dataset
      std::vector<double> row(kAlong * 3);
      for (std::size_t k = 0; k < row.size(); ++k) row[k] = 100.0 * r + 0.5 * double(k);
      series.append_row_direct(row.data(), sizeof(double));
      rows.push_back(row);
    }
    EXPECT_EQ(series.written(), 3u);
  }
  h5::Id file = h5::open_file_read(path);
  h5::Id set = h5::open_dataset(file.get(), "vectors");
  ASSERT_EQ(h5::dims_of(set.get())[0], 4u);  // grown to twice the plan
  std::vector<double> back(kAlong * 3);
  for (hsize_t r = 0; r < 3; ++r) {
    h5::read_rows(set.get(), H5T_NATIVE_DOUBLE, back.data(), r, 1);
    EXPECT_EQ(back, rows[r]) << "row " << r;
  }
  h5::read_rows(set.get(), H5T_NATIVE_DOUBLE, back.data(), 3, 1);  // planned, never written
  EXPECT_TRUE(std::all_of(back.begin(), back.end(), [](double v) { return std::isnan(v); }));
  fs::remove_all(dir);
}

TEST(ResultsCompression, CompressedFramesAreDeflatedSmallerAndReadTheSame) {
  h5::QuietErrors quiet;
  register_outputs();
  const fs::path raw_dir = fresh_dir("raw"), packed_dir = fresh_dir("packed");
  json packed_job = kPlateJob;
  packed_job["output"]["compress"] = true;
  ExecuteOptions options;
  options.threads = 1;
  ASSERT_EQ(execute_job(kPlateJob, raw_dir, options).run.status, "completed");
  ASSERT_EQ(execute_job(packed_job, packed_dir, options).run.status, "completed");
  h5::Id raw = h5::open_file_read(raw_dir / kResultsFile);
  h5::Id packed = h5::open_file_read(packed_dir / kResultsFile);
  std::uint64_t stored_raw = 0, stored_packed = 0;
  for (const FieldSpec& spec : kFrameFields) {
    const std::string name = std::string("frames/") + spec.name;
    h5::Id a = h5::open_dataset(raw.get(), name), b = h5::open_dataset(packed.get(), name);
    EXPECT_TRUE(h5::has_deflate(b.get())) << spec.name;
    stored_raw += H5Dget_storage_size(a.get());
    stored_packed += H5Dget_storage_size(b.get());
  }
  // Shuffle + deflate: ~1.4x on stresses, ~1.8x on vectors (z = 0), ~50x on ids.
  EXPECT_LT(stored_packed, stored_raw * 3 / 4);
  // Lossless: the same fields, bit for bit.
  const ResultsFile fa(raw_dir / kResultsFile), fb(packed_dir / kResultsFile);
  ASSERT_EQ(fa.frame_count(), fb.frame_count());
  const std::size_t last = fa.frame_count() - 1;
  EXPECT_EQ(fa.field(last, "von_mises"), fb.field(last, "von_mises"));
  EXPECT_EQ(fa.field(last, "position"), fb.field(last, "position"));
  fs::remove_all(raw_dir);
  fs::remove_all(packed_dir);
}

TEST_F(ResultsRun, EstimateIsAnUpperBound) {
  const std::uint64_t size = fs::file_size(dir_ / kResultsFile);
  const std::uint64_t n = state(0).particles.n;
  const std::uint64_t raw = planned_frames_ * n * 136;  // bytes per particle and frame
  EXPECT_GE(estimate_, size);
  EXPECT_GE(estimate_, raw);
  EXPECT_LT(estimate_, 2 * raw + (2u << 20)) << "an upper bound, but not a wild one";
}

TEST_F(ResultsRun, XdmfIsWellFormedAndPointsAtTheData) {
  const ResultsFile file(dir_ / kResultsFile);
  const XmlNode root = XmlReader(read_text(dir_ / kXdmfFile)).document();
  EXPECT_EQ(root.name, "Xdmf");
  EXPECT_EQ(root.attrs.at("Version"), "2.0");
  const XmlNode& series = root.child("Domain").child("Grid");
  EXPECT_EQ(series.attrs.at("GridType"), "Collection");
  EXPECT_EQ(series.attrs.at("CollectionType"), "Temporal");
  ASSERT_EQ(series.children.size(), file.frame_count());

  h5::QuietErrors quiet;
  h5::Id h5file = h5::open_file_read(dir_ / kResultsFile);
  const std::string n = std::to_string(file.particle_count());
  const std::string frames = std::to_string(file.frame_count());
  for (std::size_t k = 0; k < series.children.size(); ++k) {
    const XmlNode& grid = series.children[k];
    EXPECT_EQ(grid.attrs.at("GridType"), "Uniform");
    EXPECT_EQ(std::stod(grid.child("Time").attrs.at("Value")), file.frame_times()[k]);
    const XmlNode& topology = grid.child("Topology");
    EXPECT_EQ(topology.attrs.at("TopologyType"), "Polyvertex");
    EXPECT_EQ(topology.attrs.at("NumberOfElements"), n);
    EXPECT_EQ(grid.child("Geometry").attrs.at("GeometryType"), "XYZ");
    std::set<std::string> seen;
    for (const XmlNode& item : grid.children) {
      if (item.name != "Geometry" && item.name != "Attribute") continue;
      const XmlNode& slab = item.child("DataItem");
      ASSERT_EQ(slab.attrs.at("ItemType"), "HyperSlab");
      ASSERT_EQ(slab.children.size(), 2u);
      const std::string ref = slab.children[1].text;
      ASSERT_EQ(ref.rfind("results.h5:/frames/", 0), 0u) << ref;
      const std::string name = ref.substr(std::strlen("results.h5:/frames/"));
      seen.insert(name);
      const bool vec = name == "position" || name == "velocity" || name == "displacement";
      if (item.name == "Attribute") {
        EXPECT_EQ(item.attrs.at("Name"), name);
        EXPECT_EQ(item.attrs.at("AttributeType"), vec ? "Vector" : "Scalar");
        EXPECT_EQ(item.attrs.at("Center"), "Node");
      } else {
        EXPECT_EQ(name, "position");
      }
      EXPECT_EQ(slab.attrs.at("Dimensions"), vec ? n + " 3" : n);
      const std::vector<double> select = numbers(slab.children[0].text);
      const std::vector<double> want =
          vec ? std::vector<double>{double(k), 0, 0, 1, 1, 1, 1, double(file.particle_count()), 3}
              : std::vector<double>{double(k), 0, 1, 1, 1, double(file.particle_count())};
      EXPECT_EQ(select, want) << name;
      EXPECT_EQ(slab.children[1].attrs.at("Format"), "HDF");
      EXPECT_EQ(slab.children[1].attrs.at("Dimensions"), frames + " " + (vec ? n + " 3" : n));
      EXPECT_EQ(slab.children[1].attrs.at("NumberType"),
                name == "body_id" || name == "particle_id" ? "Int" : "Float");
      // The dataset exists with the declared shape.
      h5::Id set = h5::open_dataset(h5file.get(), "frames/" + name);
      std::vector<hsize_t> want_dims{file.frame_count(), file.particle_count()};
      if (vec) want_dims.push_back(3);
      EXPECT_EQ(h5::dims_of(set.get()), want_dims) << name;
    }
    EXPECT_EQ(seen.size(), kFrameFields.size());
  }
}

// ---------------------------------------------------------------------------

TEST(ResultsReader, RefusesMissingAndForeignFiles) {
  const fs::path dir = fresh_dir("reader");
  auto message = [](const fs::path& p) -> std::string {
    try {
      ResultsFile file(p);
    } catch (const ResultsError& e) {
      return e.what();
    }
    return "(no error)";
  };
  EXPECT_NE(message(dir / "absent.h5").find("results file not found"), std::string::npos);
  std::ofstream(dir / "text.h5") << "not hdf5\n";
  EXPECT_NE(message(dir / "text.h5").find("not a GearSPH results file"), std::string::npos);
  {
    h5::QuietErrors quiet;
    h5::Id f = h5::create_file(dir / "other.h5");
    h5::create_group(f.get(), "data");
  }
  EXPECT_NE(message(dir / "other.h5").find("not a GearSPH results file"), std::string::npos)
      << message(dir / "other.h5");
  fs::remove_all(dir);
}

TEST(ResultsReader, RefusesBadFrameAndFieldRequests) {
  register_outputs();
  const fs::path dir = fresh_dir("requests");
  json job = kPlateJob;
  job["output"]["frames"] = 2;
  execute_job(job, dir, ExecuteOptions{1, nullptr});
  const ResultsFile file(dir / kResultsFile);
  EXPECT_THROW(file.frame(file.frame_count()), ResultsError);
  EXPECT_THROW(file.field(0, "temperature"), ResultsError);
  EXPECT_THROW(file.field(0, "body_id"), ResultsError);  // an int32 field
  EXPECT_EQ(file.int_field(0, "body_id").size(), file.particle_count());
  EXPECT_THROW(file.history("no_such_column"), ResultsError);
  fs::remove_all(dir);
}

TEST(ResultsWriter, RunWithoutFramesStillRecordsHistories) {
  register_outputs();
  const fs::path dir = fresh_dir("noframes");
  json job = kPlateJob;
  job["output"]["frames"] = 0;
  const Execution e = execute_job(job, dir, ExecuteOptions{1, nullptr});
  const ResultsFile file(dir / kResultsFile);
  EXPECT_EQ(file.frame_count(), 0u);
  EXPECT_EQ(file.history_rows(), e.run.history.rows());
  EXPECT_FALSE(fs::exists(dir / kXdmfFile));
  fs::remove_all(dir);
}

// Stops the run once it passes `step` (checked every 64 steps by the runner).
class CancelAfter : public RunObserver {
 public:
  explicit CancelAfter(std::int64_t step) : step_(step) {}
  void on_sample(const Simulation& sim, const History&) override { now_ = sim.step; }
  bool cancelled() override { return now_ >= step_; }

 private:
  std::int64_t step_, now_ = 0;
};

// Fails the run at its first sample after `step`, as a full disk would.
class FailAfter : public RunObserver {
 public:
  explicit FailAfter(std::int64_t step) : step_(step) {}
  void on_sample(const Simulation& sim, const History&) override {
    if (sim.step >= step_) throw std::runtime_error("no space left on device");
  }

 private:
  std::int64_t step_;
};

TEST(ResultsWriter, ARunThatFailsInAReusedDirectoryLeavesNoSummary) {
  // summary.json says "these files are a whole run": a failed run must not
  // leave the previous run's summary next to its own partial files.
  register_outputs();
  const fs::path dir = fresh_dir("reused");
  ASSERT_EQ(execute_job(kPlateJob, dir, ExecuteOptions{1, nullptr}).run.status, "completed");
  ASSERT_TRUE(fs::exists(dir / "summary.json"));
  FailAfter fail(100);
  EXPECT_THROW(execute_job(kPlateJob, dir, ExecuteOptions{1, &fail}), std::runtime_error);
  EXPECT_FALSE(fs::exists(dir / "summary.json"));
  fs::remove_all(dir);
}

TEST(ResultsWriter, RunThatEndsEarlyKeepsItsFramesAndSaysSo) {
  register_outputs();
  const fs::path dir = fresh_dir("cancelled");
  CancelAfter cancel(200);
  const Execution e = execute_job(kPlateJob, dir, ExecuteOptions{1, &cancel});
  ASSERT_EQ(e.run.status, "cancelled");
  const ResultsFile file(dir / kResultsFile);
  const PreparedJob planned = prepare_job(kPlateJob, 1);
  EXPECT_EQ(file.status(), "cancelled");
  EXPECT_EQ(file.steps_done(), e.run.steps_done);
  EXPECT_GT(file.frame_count(), 1u);
  EXPECT_LT(file.frame_count(), static_cast<std::size_t>(planned.frames));
  EXPECT_EQ(file.history_rows(), e.run.history.rows());
  EXPECT_EQ(file.history("time_s"), e.run.history.column("time_s"));
  {
    // The frames planned but never written hold the fill value.
    h5::QuietErrors quiet;
    h5::Id f = h5::open_file_read(dir / kResultsFile);
    h5::Id vm = h5::open_dataset(f.get(), "frames/von_mises");
    EXPECT_EQ(h5::dims_of(vm.get())[0], static_cast<hsize_t>(planned.frames));
    std::vector<double> row(file.particle_count());
    h5::read_rows(vm.get(), H5T_NATIVE_DOUBLE, row.data(), file.frame_count(), 1);
    EXPECT_TRUE(std::all_of(row.begin(), row.end(), [](double v) { return std::isnan(v); }));
  }
  const XmlNode root = XmlReader(read_text(dir / kXdmfFile)).document();
  EXPECT_EQ(root.child("Domain").child("Grid").children.size(), file.frame_count());
  fs::remove_all(dir);
}

TEST(ResultsWriter, HistoryUnitsComeFromColumnSuffixes) {
  EXPECT_EQ(HistoryStore::unit_of("time_s"), "s");
  EXPECT_EQ(HistoryStore::unit_of("max_von_mises_Pa"), "Pa");
  EXPECT_EQ(HistoryStore::unit_of("kinetic_J_per_m"), "J/m");
  EXPECT_EQ(HistoryStore::unit_of("momentum_x_kg_m_s"), "kg*m/s");
  EXPECT_EQ(HistoryStore::unit_of("tip_vy_m_s"), "m/s");
  EXPECT_EQ(HistoryStore::unit_of("tip_y_m"), "m");
  EXPECT_EQ(HistoryStore::unit_of("pinion_torque_Nm"), "N*m");
  EXPECT_EQ(HistoryStore::unit_of("count"), "");
  EXPECT_EQ(HistoryStore::dataset_name("force/body"), "force_body");
}

// Outlines are found at compile time: scene types without the member, and
// scenes whose list is empty (the plate), write no /outlines group.
struct FakeOutline {
  std::string name;
  int body;
  std::vector<std::array<double, 2>> points;
  bool closed;
};
struct SceneWithOutlines {
  std::vector<FakeOutline> outlines;
};
struct SceneWithout {};

TEST(ResultsWriter, OutlinesAreWrittenWhenTheSceneHasThem) {
  const fs::path dir = fresh_dir("outlines");
  h5::QuietErrors quiet;
  {
    h5::Id f = h5::create_file(dir / "with.h5");
    SceneWithOutlines scene{{{"pinion_tooth", 0, {{0.0, 1.0}, {2.0, 3.0}, {4.0, 5.0}}, true},
                             {"rack_edge", 1, {{-1.0, 0.5}}, false}}};
    write_scene_outlines(f.get(), scene);
    h5::Id g = h5::create_file(dir / "without.h5");
    write_scene_outlines(g.get(), SceneWithout{});
    h5::Id e = h5::create_file(dir / "empty.h5");
    write_scene_outlines(e.get(), SceneWithOutlines{});
  }
  const std::vector<StoredOutline> read = read_outlines(h5::open_file_read(dir / "with.h5").get());
  ASSERT_EQ(read.size(), 2u);
  EXPECT_EQ(read[0].name, "pinion_tooth");
  EXPECT_EQ(read[0].body, 0);
  EXPECT_TRUE(read[0].closed);
  EXPECT_EQ(read[0].points, (std::vector<std::array<double, 2>>{{0, 1}, {2, 3}, {4, 5}}));
  EXPECT_EQ(read[1].name, "rack_edge");
  EXPECT_EQ(read[1].body, 1);
  EXPECT_FALSE(read[1].closed);
  EXPECT_EQ(read[1].points.size(), 1u);
  h5::Id without = h5::open_file_read(dir / "without.h5");
  EXPECT_FALSE(h5::has_link(without.get(), "outlines"));
  h5::Id empty = h5::open_file_read(dir / "empty.h5");
  EXPECT_FALSE(h5::has_link(empty.get(), "outlines"));
  fs::remove_all(dir);
}

TEST(ResultsWriter, XdmfDocumentOfNoFramesIsStillWellFormed) {
  const XmlNode root = XmlReader(xdmf_document("results.h5", 5, {}, 0)).document();
  EXPECT_TRUE(root.child("Domain").child("Grid").children.empty());
  EXPECT_THROW(XmlReader("<a><b></a>").document(), std::runtime_error);  // the checker checks
}

// ---------------------------------------------------------------------------
// SIGKILL at random moments. The job writes a frame every two steps, so most
// kills land inside the writer; every run uses one thread, which makes the
// killed runs' frames bit-identical to the reference run's.

// A 0.1 m x 0.01 m plate run for the crash tests.
json crash_job(const std::string& name, double spacing_m, double end_s, int frames) {
  return {{"name", name},
          {"scene", {{"type", "plate"}, {"length_m", 0.1}, {"thickness_m", 0.01}}},
          {"discretization", {{"spacing_m", spacing_m}}},
          {"time", {{"end_s", end_s}}},
          {"output", {{"frames", frames}}}};
}

const json kCrashJob = crash_job("crash", 0.0015, 0.01, 500);

// `gearsph run job --out out` on one thread, with `extra_env` added to this
// process's environment.
pid_t spawn_run(const fs::path& job, const fs::path& out,
                const std::vector<std::string>& extra_env = {}) {
  const std::string bin = GEARSPH_BINARY, j = job.string(), o = out.string();
  std::vector<char*> argv = {
      const_cast<char*>(bin.c_str()), const_cast<char*>("run"),     const_cast<char*>(j.c_str()),
      const_cast<char*>("--out"),     const_cast<char*>(o.c_str()), const_cast<char*>("--threads"),
      const_cast<char*>("1"),         const_cast<char*>("--quiet"), nullptr};
  std::vector<char*> env;
  auto overridden = [&](std::string_view e) {
    return std::any_of(extra_env.begin(), extra_env.end(), [&](const std::string& x) {
      return x.substr(0, x.find('=') + 1) == e.substr(0, e.find('=') + 1);
    });
  };
  for (char** e = environ; *e; ++e) {
    if (!overridden(*e)) env.push_back(*e);
  }
  for (const std::string& e : extra_env) env.push_back(const_cast<char*>(e.c_str()));
  env.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
  pid_t pid = -1;
  const int rc = posix_spawn(&pid, bin.c_str(), &actions, nullptr, argv.data(), env.data());
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) throw std::runtime_error("cannot start " + bin);
  return pid;
}

int wait_for(pid_t pid) {
  int status = 0;
  waitpid(pid, &status, 0);
  return status;
}

// The reference run, read once.
struct Reference {
  explicit Reference(const fs::path& path) : file(path) {
    for (std::size_t k = 0; k < file.frame_count(); ++k) frames.push_back(file.frame(k));
    for (const std::string& c : file.history_columns()) histories.push_back(file.history(c));
  }
  ResultsFile file;
  std::vector<Frame> frames;
  std::vector<std::vector<double>> histories;
};

// "" if equal, else the first difference.
template <class T>
std::string difference(const char* name, const std::vector<T>& got, const std::vector<T>& want) {
  if (got.size() != want.size()) return std::string(name) + ": size differs";
  for (std::size_t i = 0; i < got.size(); ++i) {
    if (std::memcmp(&got[i], &want[i], sizeof(T)) != 0) {
      std::ostringstream s;
      s.precision(17);
      s << name << "[" << i << "] = " << got[i] << ", reference " << want[i];
      return s.str();
    }
  }
  return "";
}

std::string frame_difference(const Frame& a, const Frame& b) {
  if (a.step != b.step || a.time_s != b.time_s) return "step or time differs";
  for (const std::string& d :
       {difference("position", a.position, b.position),
        difference("velocity", a.velocity, b.velocity),
        difference("displacement", a.displacement, b.displacement),
        difference("stress_xx", a.stress_xx, b.stress_xx),
        difference("stress_yy", a.stress_yy, b.stress_yy),
        difference("stress_xy", a.stress_xy, b.stress_xy),
        difference("stress_zz", a.stress_zz, b.stress_zz),
        difference("pressure", a.pressure, b.pressure),
        difference("von_mises", a.von_mises, b.von_mises),
        difference("density", a.density, b.density), difference("body_id", a.body_id, b.body_id),
        difference("particle_id", a.particle_id, b.particle_id)}) {
    if (!d.empty()) return d;
  }
  return "";
}

// Every frame and history row of `got` equals the reference's, bit for bit.
void expect_prefix_of(const ResultsFile& got, const Reference& ref) {
  ASSERT_LE(got.frame_count(), ref.frames.size());
  ASSERT_EQ(got.particle_count(), ref.file.particle_count());
  for (std::size_t k = 0; k < got.frame_count(); ++k) {
    ASSERT_EQ(frame_difference(got.frame(k), ref.frames[k]), "")
        << "frame " << k << " of " << got.frame_count() << " in " << got.path();
  }
  ASSERT_EQ(got.history_columns(), ref.file.history_columns());
  ASSERT_LE(got.history_rows(), ref.file.history_rows());
  for (std::size_t c = 0; c < ref.histories.size(); ++c) {
    const std::vector<double> g = got.history(got.history_columns()[c]);
    ASSERT_TRUE(std::equal(g.begin(), g.end(), ref.histories[c].begin())) << "column " << c;
  }
}

// True if `tool args` succeeds; a tool that is not installed is not asked.
bool tool_accepts(const std::string& tool, const std::string& args) {
  if (std::system(("command -v " + tool + " >/dev/null 2>&1").c_str()) != 0) return true;
  return std::system((tool + " " + args + " >/dev/null 2>&1").c_str()) == 0;
}

TEST(ResultsCrash, KilledRunsKeepEveryCommittedFrame) {
  const fs::path dir = fresh_dir("crash");
  const fs::path job = dir / "job.json";
  std::ofstream(job) << kCrashJob.dump();

  const auto start = std::chrono::steady_clock::now();
  ASSERT_EQ(wait_for(spawn_run(job, dir / "reference")), 0);
  const double run_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const Reference ref(dir / "reference" / kResultsFile);
  ASSERT_GT(ref.frames.size(), 300u);

  const unsigned seed = std::random_device{}();
  std::mt19937 rng(seed);
  // Runs vary in speed on a shared machine: stop short of the end.
  std::uniform_real_distribution<double> when(0.05 * run_s, 0.8 * run_s);
  constexpr int kTrials = 6;
  for (int trial = 0; trial < kTrials; ++trial) {
    const double kill_s = when(rng);
    SCOPED_TRACE("seed " + std::to_string(seed) + ", trial " + std::to_string(trial) +
                 ", kill after " + std::to_string(kill_s) + " s of ~" + std::to_string(run_s));
    const fs::path out = dir / ("killed" + std::to_string(trial));
    const pid_t pid = spawn_run(job, out);
    std::this_thread::sleep_for(std::chrono::duration<double>(kill_s));
    // A reader may open the file of a running job (if it catches a flush
    // mid-way it may fail; then it is the caller's to retry).
    if (fs::exists(out / kResultsFile)) {
      try {
        SCOPED_TRACE("read while running");
        expect_prefix_of(ResultsFile(out / kResultsFile), ref);
      } catch (const ResultsError& e) {
        std::printf("  live read failed (retry is the caller's): %s\n", e.what());
      }
    }
    ::kill(pid, SIGKILL);
    const int status = wait_for(pid);
    if (WIFEXITED(status)) {
      std::printf("  trial %d: finished before the kill at %.2f s\n", trial, kill_s);
      continue;
    }
    ASSERT_TRUE(WIFSIGNALED(status));
    if (!fs::exists(out / kResultsFile)) {
      std::printf("  trial %d: killed at %.2f s before results.h5 was complete\n", trial, kill_s);
      EXPECT_FALSE(fs::exists(out / kXdmfFile)) << "an xmf without its results.h5";
      continue;
    }
    SCOPED_TRACE("read after the kill");
    const ResultsFile killed(out / kResultsFile);
    if (killed.status() == "completed") {
      // Killed after the run had completed its file, while the process
      // wrote its summary and exited: then every frame and row is there.
      EXPECT_EQ(killed.frame_count(), ref.frames.size());
      EXPECT_EQ(killed.history_rows(), ref.file.history_rows());
    } else {
      EXPECT_EQ(killed.status(), "running");
    }
    expect_prefix_of(killed, ref);
    std::printf("  trial %d: killed after %.2f s with %zu of %zu frames, %zu history rows\n", trial,
                kill_s, killed.frame_count(), ref.frames.size(), killed.history_rows());
    if (fs::exists(out / kXdmfFile)) {
      const XmlNode root = XmlReader(read_text(out / kXdmfFile)).document();
      const std::size_t xmf_frames = root.child("Domain").child("Grid").children.size();
      EXPECT_GE(xmf_frames, 1u);
      EXPECT_LE(xmf_frames, killed.frame_count());
    }
    const std::string file = (out / kResultsFile).string();
    EXPECT_TRUE(tool_accepts("h5ls", "-r " + file));
    EXPECT_TRUE(tool_accepts("h5dump", "-H " + file));
    EXPECT_TRUE(tool_accepts("h5dump", "-d /frames/step " + file));
  }
  if (!HasFailure()) fs::remove_all(dir);  // kept for a post-mortem otherwise
}

// ---------------------------------------------------------------------------
// SIGKILL between every two writes of a run (tests/support/crash_at_write.cpp,
// preloaded): the moments random kills almost never reach, inside a flush.

const json kCrashPointJob = crash_job("crash-points", 0.002, 0.0008, 8);

std::vector<std::string> preload_env(const std::string& setting) {
  // A sanitized gearsph wants its runtime first in the library list; the
  // preloaded library only wraps pwrite.
  const char* asan = std::getenv("ASAN_OPTIONS");
  return {std::string("LD_PRELOAD=") + GEARSPH_CRASH_SHIM, setting,
          std::string("ASAN_OPTIONS=") + (asan ? std::string(asan) + ":" : "") +
              "verify_asan_link_order=0"};
}

TEST(ResultsCrash, KilledBetweenAnyTwoWritesLeavesAReadableFile) {
  const fs::path dir = fresh_dir("crash-points");
  const fs::path job = dir / "job.json";
  std::ofstream(job) << kCrashPointJob.dump();
  const fs::path count_file = dir / "writes.txt";
  ASSERT_EQ(wait_for(spawn_run(job, dir / "reference",
                               preload_env("GEARSPH_WRITE_COUNT_FILE=" + count_file.string()))),
            0);
  long writes = 0;
  std::ifstream(count_file) >> writes;
  ASSERT_GT(writes, 50) << "the preloaded library saw no writes: HDF5 no longer uses pwrite?";
  const Reference ref(dir / "reference" / kResultsFile);
  ASSERT_EQ(ref.frames.size(), 9u);  // the initial state and 8 more

  // At most ~160 runs: every write of a small run, or every few of a larger.
  const long stride = std::max(1L, writes / 160);
  std::size_t before_publish = 0, readable = 0;
  std::set<std::size_t> frames_seen;
  for (long at = 1; at <= writes; at += stride) {
    SCOPED_TRACE("killed before write " + std::to_string(at) + " of " + std::to_string(writes));
    const fs::path out = dir / "killed";
    fs::remove_all(out);
    const int status =
        wait_for(spawn_run(job, out, preload_env("GEARSPH_CRASH_AT_WRITE=" + std::to_string(at))));
    ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL);
    if (!fs::exists(out / kResultsFile)) {
      ++before_publish;
      EXPECT_FALSE(fs::exists(out / kXdmfFile)) << "an xmf without its results.h5";
      continue;
    }
    std::optional<ResultsFile> killed;
    try {
      killed.emplace(out / kResultsFile);
      EXPECT_EQ(killed->status(), "running");
      expect_prefix_of(*killed, ref);
    } catch (const ResultsError& e) {
      ADD_FAILURE() << "killed before write " << at << ": unreadable: " << e.what();
    }
    if (HasFailure()) break;
    frames_seen.insert(killed->frame_count());
    ++readable;
    if (at % (25 * stride) == 1) {
      EXPECT_TRUE(tool_accepts("h5ls", "-r " + (out / kResultsFile).string()));
    }
  }
  std::printf(
      "  %ld writes, %zu crash points: %zu before results.h5 was published, %zu readable, "
      "frame counts seen %zu..%zu\n",
      writes, before_publish + readable, before_publish, readable,
      frames_seen.empty() ? 0 : *frames_seen.begin(),
      frames_seen.empty() ? 0 : *frames_seen.rbegin());
  // The sweep reached every stage: before any frame, between frames, all.
  EXPECT_GT(readable, 50u);
  EXPECT_TRUE(frames_seen.count(0) && frames_seen.count(4) && frames_seen.count(8));
  if (!HasFailure()) fs::remove_all(dir);
}

}  // namespace
}  // namespace gearsph::results
