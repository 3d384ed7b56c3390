#include "results/frame_store.hpp"

#include <algorithm>
#include <limits>

#include "results/results_layout.hpp"

namespace gearsph::results {

namespace {

h5::Series field_series(hid_t group, const FieldSpec& f, std::size_t n, hsize_t frames,
                        bool compress) {
  const hsize_t chunk_n = std::min(n, FrameStore::kChunkParticles);
  h5::Series::Shape shape;
  shape.row = {n};
  shape.chunk = {1, chunk_n};
  if (f.components == 3) {
    shape.row.push_back(3);
    shape.chunk.push_back(3);
  }
  shape.compress = compress;
  if (f.integer) {
    const std::int32_t fill = -1;
    return h5::Series(group, f.name, H5T_STD_I32LE, shape, frames, &fill);
  }
  const double fill = std::numeric_limits<double>::quiet_NaN();
  return h5::Series(group, f.name, H5T_IEEE_F64LE, shape, frames, &fill);
}

// out[3i..3i+2] = (fx(i), fy(i), 0): the 2D vectors as XDMF's XYZ wants them.
template <class Fx, class Fy>
void gather_xyz(std::vector<double>& out, std::size_t n, Fx fx, Fy fy) {
  for (std::size_t i = 0; i < n; ++i) {
    out[3 * i] = fx(i);
    out[3 * i + 1] = fy(i);
    out[3 * i + 2] = 0.0;
  }
}

template <class F>
void gather(std::vector<double>& out, std::size_t n, F f) {
  for (std::size_t i = 0; i < n; ++i) out[i] = f(i);
}

}  // namespace

std::uint64_t FrameStore::chunks_per_frame(std::size_t particles) {
  return (particles + kChunkParticles - 1) / kChunkParticles;
}

FrameStore::FrameStore(hid_t file, std::size_t particles, std::size_t frames, bool compress)
    : group_(h5::create_group(file, "frames")),
      compress_(compress),
      values_(3 * particles),
      ints_(particles) {
  for (const FieldSpec& f : kFrameFields) {
    fields_.push_back(field_series(group_.get(), f, particles, frames, compress));
  }
  h5::Series::Shape marker;
  marker.chunk = {kMarkerChunkRows};
  const double no_time = std::numeric_limits<double>::quiet_NaN();
  const std::int64_t no_step = -1;
  time_ = h5::Series(group_.get(), "time", H5T_IEEE_F64LE, marker, frames, &no_time);
  step_ = h5::Series(group_.get(), "step", H5T_STD_I64LE, marker, frames, &no_step);
}

void FrameStore::write_fields(const Simulation& sim) {
  for (std::size_t k = 0; k < kFrameFields.size(); ++k) write_field(k, sim.particles);
}

void FrameStore::write_field(std::size_t k, const Particles& p) {
  const std::size_t n = p.n;
  auto& v = values_;
  switch (k) {
    case 0:
      gather_xyz(
          v, n, [&](auto i) { return p.x[i]; }, [&](auto i) { return p.y[i]; });
      break;
    case 1:
      gather_xyz(
          v, n, [&](auto i) { return p.vx[i]; }, [&](auto i) { return p.vy[i]; });
      break;
    case 2:
      gather_xyz(
          v, n, [&](auto i) { return p.x[i] - p.x0[i]; }, [&](auto i) { return p.y[i] - p.y0[i]; });
      break;
    case 3:
      gather(v, n, [&](auto i) { return p.sigma_xx(i); });
      break;
    case 4:
      gather(v, n, [&](auto i) { return p.sigma_yy(i); });
      break;
    case 5:
      gather(v, n, [&](auto i) { return p.sigma_xy(i); });
      break;
    case 6:
      gather(v, n, [&](auto i) { return p.sigma_zz(i); });
      break;
    case 7:
      gather(v, n, [&](auto i) { return p.p[i]; });
      break;
    case 8:
      gather(v, n, [&](auto i) { return p.von_mises(i); });
      break;
    case 9:
      gather(v, n, [&](auto i) { return p.rho[i]; });
      break;
    case 10:
      std::copy(p.body.begin(), p.body.end(), ints_.begin());
      break;
    // Particles are never reordered, so a particle's id is its index.
    case 11:
      for (std::size_t i = 0; i < n; ++i) ints_[i] = static_cast<std::int32_t>(i);
      break;
  }
  const bool integer = kFrameFields[k].integer;
  if (compress_) {  // through the filters
    if (integer) {
      fields_[k].append(ints_, 1);
    } else {
      fields_[k].append(values_, 1);
    }
  } else if (integer) {
    fields_[k].append_row_direct(ints_.data(), sizeof(std::int32_t));
  } else {
    fields_[k].append_row_direct(values_.data(), sizeof(double));
  }
}

void FrameStore::commit(const Simulation& sim) {
  time_.append(&sim.time, H5T_NATIVE_DOUBLE, 1);
  step_.append(&sim.step, H5T_NATIVE_INT64, 1);
}

}  // namespace gearsph::results
