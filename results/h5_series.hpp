#pragma once
// A dataset filled row by row along axis 0 (frames, history samples) whose
// planned rows are all allocated when it is created (H5D_ALLOC_TIME_EARLY,
// each chunk holding the fill value). Its chunk index is therefore complete
// from the start: writing a row replaces that row's index entries in place
// and never inserts or splits a node (results_writer.hpp says why that
// matters). Rows not yet written read as the fill value.
#include <string>
#include <vector>

#include "results/h5_util.hpp"

namespace gearsph::results::h5 {

class Series {
 public:
  struct Shape {
    std::vector<hsize_t> row;    // dimensions of one row (empty: a scalar per row)
    std::vector<hsize_t> chunk;  // full-rank chunk shape, axis 0 first
    bool compress = false;
  };

  Series() = default;
  // Creates the dataset with `rows` rows allocated, unlimited along axis 0.
  // `fill` points to one value of `type`.
  Series(hid_t parent, const std::string& name, hid_t type, const Shape& shape, hsize_t rows,
         const void* fill);

  // Writes rows [written, written + count) from `data` (count x row
  // elements of `mem_type`). Past the planned rows the dataset grows, which
  // allocates chunks and inserts index entries: outside the plan, outside
  // the crash guarantee.
  void append(const void* data, hid_t mem_type, hsize_t count);
  template <class T>
  void append(const std::vector<T>& data, hsize_t count) {
    append(data.data(), native_type<T>(), count);
  }
  // The same for one row of an uncompressed dataset whose chunks hold one
  // row each, written chunk by chunk straight to the file (H5Dwrite_chunk):
  // no selection, no chunk cache, so the flush after it has only the index
  // entries to write. `data` holds the row in the file's (little-endian)
  // layout, `element_bytes` per element.
  void append_row_direct(const void* data, std::size_t element_bytes);
  hsize_t written() const { return written_; }
  hid_t id() const { return set_.get(); }

 private:
  void grow(hsize_t rows);

  Id set_;
  std::vector<hsize_t> row_, chunk_;
  bool compressed_ = false;
  std::vector<unsigned char> padded_;  // a last, partial chunk along axis 1
  hsize_t rows_ = 0, written_ = 0;
};

}  // namespace gearsph::results::h5
