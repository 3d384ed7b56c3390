#include "results/h5_series.hpp"

#include <algorithm>
#include <bit>
#include <stdexcept>

namespace gearsph::results::h5 {

namespace {

std::vector<hsize_t> with_rows(hsize_t rows, const std::vector<hsize_t>& row) {
  std::vector<hsize_t> dims{rows};
  dims.insert(dims.end(), row.begin(), row.end());
  return dims;
}

}  // namespace

Series::Series(hid_t parent, const std::string& name, hid_t type, const Shape& shape, hsize_t rows,
               const void* fill)
    : row_(shape.row), chunk_(shape.chunk), compressed_(shape.compress), rows_(rows) {
  const std::vector<hsize_t> dims = with_rows(rows, row_);
  const std::vector<hsize_t> max = with_rows(H5S_UNLIMITED, row_);
  Id space = own(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), max.data()), H5Sclose,
                 "dataspace of " + name);
  Id dcpl = dataset_properties(shape.chunk, shape.compress);
  check(H5Pset_fill_value(dcpl.get(), type, fill), "fill value of " + name);
  check(H5Pset_fill_time(dcpl.get(), H5D_FILL_TIME_ALLOC), "fill time of " + name);
  check(H5Pset_alloc_time(dcpl.get(), H5D_ALLOC_TIME_EARLY), "allocation time of " + name);
  set_ =
      own(H5Dcreate2(parent, name.c_str(), type, space.get(), H5P_DEFAULT, dcpl.get(), H5P_DEFAULT),
          H5Dclose, "create dataset " + name);
}

void Series::grow(hsize_t rows) {
  const std::vector<hsize_t> dims = with_rows(rows, row_);
  check(H5Dset_extent(set_.get(), dims.data()), "grow dataset");
  rows_ = rows;
}

void Series::append(const void* data, hid_t mem_type, hsize_t count) {
  if (count == 0) return;
  if (written_ + count > rows_) grow(std::max(written_ + count, 2 * rows_));
  std::vector<hsize_t> start(row_.size() + 1, 0);
  start[0] = written_;
  const std::vector<hsize_t> block = with_rows(count, row_);
  Id file_space = own(H5Dget_space(set_.get()), H5Sclose, "dataset space");
  check(H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, start.data(), nullptr, block.data(),
                            nullptr),
        "select rows");
  Id mem_space = own(H5Screate_simple(static_cast<int>(block.size()), block.data(), nullptr),
                     H5Sclose, "memory space");
  check(H5Dwrite(set_.get(), mem_type, mem_space.get(), file_space.get(), H5P_DEFAULT, data),
        "write rows");
  written_ += count;
}

void Series::append_row_direct(const void* data, std::size_t element_bytes) {
  static_assert(std::endian::native == std::endian::little, "rows are written as stored");
  if (compressed_ || chunk_.empty() || chunk_[0] != 1 || row_.empty() ||
      !std::equal(row_.begin() + 1, row_.end(), chunk_.begin() + 2)) {
    throw std::logic_error("append_row_direct: chunks must hold one uncompressed row");
  }
  if (written_ + 1 > rows_) grow(std::max(written_ + 1, 2 * rows_));
  // Elements after axis 1 (3 for a vector field), and chunks along axis 1.
  std::size_t inner = 1;
  for (std::size_t d = 1; d < row_.size(); ++d) inner *= row_[d];
  const std::size_t along = row_[0], per_chunk = chunk_[1];
  const std::size_t chunk_bytes = per_chunk * inner * element_bytes;
  std::vector<hsize_t> offset(row_.size() + 1, 0);
  offset[0] = written_;
  const auto* bytes = static_cast<const unsigned char*>(data);
  for (std::size_t first = 0; first < along; first += per_chunk) {
    offset[1] = first;
    const std::size_t have = std::min(per_chunk, along - first) * inner * element_bytes;
    const unsigned char* chunk = bytes + first * inner * element_bytes;
    if (have < chunk_bytes) {  // stored whole: the part past the row is padding
      padded_.assign(chunk_bytes, 0);
      std::copy(chunk, chunk + have, padded_.begin());
      chunk = padded_.data();
    }
    check(H5Dwrite_chunk(set_.get(), H5P_DEFAULT, 0, offset.data(), chunk_bytes, chunk),
          "write a row's chunk");
  }
  written_ += 1;
}

}  // namespace gearsph::results::h5
