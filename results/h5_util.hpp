#pragma once
// Thin RAII over the HDF5 C API (Debian libhdf5 1.10): every id is closed by
// its owner and every failure becomes an h5::Error carrying HDF5's own
// message. Only what results.h5 needs: groups, text/int attributes, whole
// datasets, and their creation properties.
#include <hdf5.h>

#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace gearsph::results::h5 {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// An owned hid_t, closed with the function that matches its kind.
class Id {
 public:
  using Closer = herr_t (*)(hid_t);
  Id() = default;
  Id(hid_t id, Closer close) : id_(id), close_(close) {}
  Id(Id&& o) noexcept : id_(std::exchange(o.id_, H5I_INVALID_HID)), close_(o.close_) {}
  Id& operator=(Id&& o) noexcept;
  Id(const Id&) = delete;
  Id& operator=(const Id&) = delete;
  ~Id() { reset(); }
  hid_t get() const { return id_; }
  bool valid() const { return id_ >= 0; }
  void reset();

 private:
  hid_t id_ = H5I_INVALID_HID;
  Closer close_ = nullptr;
};

// Owns `id`, or throws Error("<what>: <HDF5's innermost message>") if it is negative.
Id own(hid_t id, Id::Closer close, const std::string& what);
void check(herr_t status, const std::string& what);

// While alive, HDF5 prints nothing to stderr on this thread: our exceptions
// report the errors instead.
class QuietErrors {
 public:
  QuietErrors();
  ~QuietErrors();
  QuietErrors(const QuietErrors&) = delete;
  QuietErrors& operator=(const QuietErrors&) = delete;

 private:
  H5E_auto2_t func_ = nullptr;
  void* data_ = nullptr;
};

template <class T>
hid_t native_type();
template <>
inline hid_t native_type<double>() {
  return H5T_NATIVE_DOUBLE;
}
template <>
inline hid_t native_type<std::int32_t>() {
  return H5T_NATIVE_INT32;
}
template <>
inline hid_t native_type<std::int64_t>() {
  return H5T_NATIVE_INT64;
}
template <>
inline hid_t native_type<std::uint8_t>() {
  return H5T_NATIVE_UINT8;
}

// Files. Writers take no file lock, so ParaView or h5dump can open a
// results.h5 of a running job (locks are advisory; the commit protocol in
// results_writer.hpp is what keeps readers safe).
Id create_file(const std::filesystem::path& path);
Id open_file_read(const std::filesystem::path& path);
void flush(hid_t file);

Id create_group(hid_t parent, const std::string& name);
Id open_group(hid_t parent, const std::string& name);
Id open_dataset(hid_t parent, const std::string& name);
bool has_link(hid_t parent, const std::string& name);
bool has_attribute(hid_t object, const std::string& name);

// Attributes: text is stored as a fixed-length, null-terminated UTF-8 string
// of at least `bytes` bytes (room for a later overwrite_attribute).
void write_attribute(hid_t object, const std::string& name, const std::string& text,
                     std::size_t bytes = 0);
void write_attribute(hid_t object, const std::string& name, std::int64_t value);
void write_attribute(hid_t object, const std::string& name, const std::vector<std::string>& list);
// Overwrites an existing fixed-length text attribute in place (truncating).
void overwrite_attribute(hid_t object, const std::string& name, const std::string& text);
void overwrite_attribute(hid_t object, const std::string& name, std::int64_t value);
std::string read_text_attribute(hid_t object, const std::string& name);
std::int64_t read_int_attribute(hid_t object, const std::string& name);
std::vector<std::string> read_text_list_attribute(hid_t object, const std::string& name);

// Object creation properties for datasets: no timestamps (they would be
// rewritten with every append), optionally chunked + shuffle + deflate.
Id dataset_properties(const std::vector<hsize_t>& chunk, bool compress);
inline constexpr unsigned kDeflateLevel =
    1;  // level 1: near level-6 ratio on shuffled doubles, much faster

// Whole (fixed-size) datasets.
void write_dataset(hid_t parent, const std::string& name, hid_t mem_type, const void* data,
                   const std::vector<hsize_t>& dims, bool compress);
template <class T, class Allocator>
void write_dataset(hid_t parent, const std::string& name, const std::vector<T, Allocator>& data,
                   const std::vector<hsize_t>& dims, bool compress = false) {
  write_dataset(parent, name, native_type<T>(), data.data(), dims, compress);
}
void write_text_dataset(hid_t parent, const std::string& name,
                        const std::vector<std::string>& list);

std::vector<hsize_t> dims_of(hid_t dataset);
std::uint64_t element_count(const std::vector<hsize_t>& dims);
// Reads `count` rows starting at `first` along axis 0 (all of them by default).
void read_rows(hid_t dataset, hid_t mem_type, void* out, hsize_t first, hsize_t count);
template <class T>
std::vector<T> read_all(hid_t dataset) {
  const std::vector<hsize_t> dims = dims_of(dataset);
  std::vector<T> out(element_count(dims));
  if (!out.empty()) read_rows(dataset, native_type<T>(), out.data(), 0, dims.empty() ? 1 : dims[0]);
  return out;
}
std::vector<std::string> read_text_dataset(hid_t dataset);
// True if the dataset's creation property list has the deflate filter.
bool has_deflate(hid_t dataset);

}  // namespace gearsph::results::h5
