#include "results/results_reader.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <thread>

#include "results/results_layout.hpp"

namespace gearsph::results {

namespace {

const FieldSpec* find_field(const std::string& name) {
  for (const FieldSpec& f : kFrameFields) {
    if (name == f.name) return &f;
  }
  return nullptr;
}

// Runs `body`, turning HDF5 failures into ResultsError naming the file.
template <class F>
auto guarded(const std::filesystem::path& path, F body) {
  h5::QuietErrors quiet;
  try {
    return body();
  } catch (const h5::Error& e) {
    throw ResultsError(path.string() + ": " + e.what());
  }
}

// A file being written may be caught mid-flush (HDF5 compares the file size
// it saw with the end-of-file address in the superblock it reads a moment
// later): such an open is retried briefly.
h5::Id open_settled(const std::filesystem::path& path) {
  constexpr int kAttempts = 10;
  for (int attempt = 1;; ++attempt) {
    try {
      return h5::open_file_read(path);
    } catch (const h5::Error&) {
      if (attempt == kAttempts) throw;
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
  }
}

}  // namespace

ResultsFile::ResultsFile(const std::filesystem::path& path) : path_(path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    throw ResultsError("results file not found: " + path.string());
  }
  guarded(path_, [&] {
    if (H5Fis_hdf5(path.c_str()) <= 0) {
      throw ResultsError(path.string() + " is not a GearSPH results file (not HDF5)");
    }
    {
      const h5::Id index = open_settled(path_);
      check_format(index.get());
      read_frame_index(index.get());
      read_history_index(index.get());
    }
    // Opened again for the data: this superblock is at least as recent as
    // the commit markers just read, so every committed chunk lies within
    // the end of file it states (a running writer appends beyond it).
    file_ = open_settled(path_);
    meta_ = h5::open_group(file_.get(), "meta");
    particles_ = static_cast<std::size_t>(h5::read_int_attribute(meta(), "particles"));
    return 0;
  });
}

void ResultsFile::check_format(hid_t f) const {
  if (!h5::has_link(f, "meta") || !h5::has_attribute(h5::open_group(f, "meta").get(), "format") ||
      h5::read_text_attribute(h5::open_group(f, "meta").get(), "format") != kFormatName) {
    throw ResultsError(path_.string() + " is not a GearSPH results file (no /meta format \"" +
                       kFormatName + "\")");
  }
  const auto version = h5::read_int_attribute(h5::open_group(f, "meta").get(), "format_version");
  if (version > kFormatVersion) {
    throw ResultsError(path_.string() + " has results format version " + std::to_string(version) +
                       "; this build reads up to " + std::to_string(kFormatVersion));
  }
}

// Committed frames: those whose step marker was written (results_writer.hpp),
// and no more than every field holds.
void ResultsFile::read_frame_index(hid_t f) {
  steps_ = h5::read_all<std::int64_t>(h5::open_dataset(f, "frames/step").get());
  times_ = h5::read_all<double>(h5::open_dataset(f, "frames/time").get());
  std::size_t n = std::min(steps_.size(), times_.size());
  for (const FieldSpec& spec : kFrameFields) {
    const auto dims = h5::dims_of(h5::open_dataset(f, std::string("frames/") + spec.name).get());
    n = std::min<std::size_t>(n, dims.at(0));
  }
  std::size_t valid = 0;
  while (valid < n && steps_[valid] >= 0 && std::isfinite(times_[valid])) ++valid;
  steps_.resize(valid);
  times_.resize(valid);
}

// Committed rows: the valid prefix of the first column (time_s), and no
// more than every column holds.
void ResultsFile::read_history_index(hid_t f) {
  if (!h5::has_link(f, "histories")) return;  // killed before the first sample
  columns_ = h5::read_text_list_attribute(h5::open_group(f, "histories").get(), "columns");
  if (columns_.empty()) return;
  const auto first = h5::read_all<double>(h5::open_dataset(f, "histories/" + columns_[0]).get());
  std::size_t n = first.size();
  for (const std::string& c : columns_) {
    n = std::min<std::size_t>(n, h5::dims_of(h5::open_dataset(f, "histories/" + c).get()).at(0));
  }
  history_rows_ = 0;
  while (history_rows_ < n && !std::isnan(first[history_rows_])) ++history_rows_;
}

std::int64_t ResultsFile::format_version() const {
  return guarded(path_, [&] { return h5::read_int_attribute(meta(), "format_version"); });
}

std::string ResultsFile::solver_version() const {
  return guarded(path_, [&] { return h5::read_text_attribute(meta(), "solver_version"); });
}

std::string ResultsFile::created() const {
  return guarded(path_, [&] { return h5::read_text_attribute(meta(), "created"); });
}

std::string ResultsFile::status() const {
  return guarded(path_, [&] { return h5::read_text_attribute(meta(), "status"); });
}

std::int64_t ResultsFile::steps_done() const {
  return guarded(path_, [&] { return h5::read_int_attribute(meta(), "steps_done"); });
}

nlohmann::json ResultsFile::job() const {
  return guarded(path_,
                 [&] { return nlohmann::json::parse(h5::read_text_attribute(meta(), "job")); });
}

nlohmann::json ResultsFile::units() const {
  return guarded(path_, [&] {
    if (!h5::has_attribute(meta(), "units")) return nlohmann::json::object();
    return nlohmann::json::parse(h5::read_text_attribute(meta(), "units"));
  });
}

template <class T>
std::vector<T> ResultsFile::frame_row(std::size_t frame, const std::string& name,
                                      bool integer) const {
  const FieldSpec* spec = find_field(name);
  if (!spec || spec->integer != integer) {
    throw ResultsError("results: no " + std::string(integer ? "integer" : "float") +
                       " frame field named '" + name + "'");
  }
  if (frame >= frame_count()) {
    throw ResultsError(path_.string() + ": frame " + std::to_string(frame) + " out of range (" +
                       std::to_string(frame_count()) + " frames)");
  }
  return guarded(path_, [&] {
    h5::Id set = h5::open_dataset(file_.get(), "frames/" + name);
    std::vector<T> out(particles_ * static_cast<std::size_t>(spec->components));
    h5::read_rows(set.get(), h5::native_type<T>(), out.data(), frame, 1);
    return out;
  });
}

std::vector<double> ResultsFile::field(std::size_t frame, const std::string& name) const {
  return frame_row<double>(frame, name, false);
}

std::vector<std::int32_t> ResultsFile::int_field(std::size_t frame, const std::string& name) const {
  return frame_row<std::int32_t>(frame, name, true);
}

Frame ResultsFile::frame(std::size_t index) const {
  Frame f;
  f.index = index;
  f.position = field(index, "position");
  f.step = steps_[index];
  f.time_s = times_[index];
  f.velocity = field(index, "velocity");
  f.displacement = field(index, "displacement");
  f.stress_xx = field(index, "stress_xx");
  f.stress_yy = field(index, "stress_yy");
  f.stress_xy = field(index, "stress_xy");
  f.stress_zz = field(index, "stress_zz");
  f.pressure = field(index, "pressure");
  f.von_mises = field(index, "von_mises");
  f.density = field(index, "density");
  f.body_id = int_field(index, "body_id");
  f.particle_id = int_field(index, "particle_id");
  return f;
}

std::vector<BodyInfo> ResultsFile::bodies() const {
  return guarded(path_, [&] {
    h5::Id g = h5::open_group(file_.get(), "bodies");
    const auto names = h5::read_text_dataset(h5::open_dataset(g.get(), "name").get());
    const auto range =
        h5::read_all<std::int64_t>(h5::open_dataset(g.get(), "particle_range").get());
    const auto E = h5::read_all<double>(h5::open_dataset(g.get(), "E_Pa").get());
    const auto nu = h5::read_all<double>(h5::open_dataset(g.get(), "nu").get());
    const auto rho = h5::read_all<double>(h5::open_dataset(g.get(), "rho_kg_m3").get());
    const std::size_t b = names.size();
    if (range.size() != 2 * b || E.size() != b || nu.size() != b || rho.size() != b) {
      throw ResultsError(path_.string() + ": /bodies datasets of inconsistent lengths");
    }
    std::vector<BodyInfo> out(b);
    for (std::size_t i = 0; i < b; ++i) {
      out[i] = {names[i], range[2 * i], range[2 * i + 1], E[i], nu[i], rho[i]};
    }
    return out;
  });
}

InitialState ResultsFile::initial() const {
  return guarded(path_, [&] {
    h5::Id g = h5::open_group(file_.get(), "initial");
    InitialState s;
    s.position = h5::read_all<double>(h5::open_dataset(g.get(), "position").get());
    s.body_id = h5::read_all<std::int32_t>(h5::open_dataset(g.get(), "body_id").get());
    s.particle_id = h5::read_all<std::int32_t>(h5::open_dataset(g.get(), "particle_id").get());
    s.mass = h5::read_all<double>(h5::open_dataset(g.get(), "mass").get());
    return s;
  });
}

std::vector<StoredOutline> ResultsFile::outlines() const {
  return guarded(path_, [&] { return read_outlines(file_.get()); });
}

std::vector<double> ResultsFile::history(const std::string& column) const {
  if (std::find(columns_.begin(), columns_.end(), column) == columns_.end()) {
    throw ResultsError(path_.string() + ": no history column '" + column + "'");
  }
  return guarded(path_, [&] {
    h5::Id set = h5::open_dataset(file_.get(), "histories/" + column);
    std::vector<double> out(history_rows_);
    if (history_rows_ > 0)
      h5::read_rows(set.get(), H5T_NATIVE_DOUBLE, out.data(), 0, history_rows_);
    return out;
  });
}

}  // namespace gearsph::results
