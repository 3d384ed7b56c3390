#include "results/h5_util.hpp"

#include <algorithm>
#include <cstring>

namespace gearsph::results::h5 {

namespace {

// The deepest message on HDF5's error stack: the most specific one
// (e.g. "unable to open file: ... errno = 2").
herr_t keep_description(unsigned, const H5E_error2_t* err, void* out) {
  if (err->desc && *err->desc) *static_cast<std::string*>(out) = err->desc;
  return 0;
}

std::string hdf5_message() {
  std::string msg;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_DOWNWARD, keep_description, &msg);
  H5Eclear2(H5E_DEFAULT);
  return msg.empty() ? "HDF5 error" : msg;
}

Id text_type(std::size_t bytes) {
  Id type = own(H5Tcopy(H5T_C_S1), H5Tclose, "text type");
  check(H5Tset_size(type.get(), std::max<std::size_t>(bytes, 1)), "text type size");
  check(H5Tset_strpad(type.get(), H5T_STR_NULLTERM), "text type padding");
  check(H5Tset_cset(type.get(), H5T_CSET_UTF8), "text type charset");
  return type;
}

Id simple_space(const std::vector<hsize_t>& dims, const std::vector<hsize_t>* max = nullptr) {
  if (dims.empty()) return own(H5Screate(H5S_SCALAR), H5Sclose, "scalar dataspace");
  return own(
      H5Screate_simple(static_cast<int>(dims.size()), dims.data(), max ? max->data() : nullptr),
      H5Sclose, "dataspace");
}

Id attribute_for_write(hid_t object, const std::string& name, hid_t type, hid_t space) {
  if (H5Aexists(object, name.c_str()) > 0)
    check(H5Adelete(object, name.c_str()), "replace " + name);
  return own(H5Acreate2(object, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
             "create attribute " + name);
}

// Packs strings into fixed-length records of `width` bytes (null-padded).
std::vector<char> pack(const std::vector<std::string>& list, std::size_t width) {
  std::vector<char> buf(list.size() * width, '\0');
  for (std::size_t i = 0; i < list.size(); ++i) {
    std::memcpy(buf.data() + i * width, list[i].data(), std::min(list[i].size(), width));
  }
  return buf;
}

std::size_t widest(const std::vector<std::string>& list) {
  std::size_t w = 1;
  for (const std::string& s : list) w = std::max(w, s.size() + 1);
  return w;
}

std::vector<std::string> unpack(const std::vector<char>& buf, std::size_t width) {
  std::vector<std::string> out;
  for (std::size_t at = 0; at + width <= buf.size(); at += width) {
    out.emplace_back(buf.data() + at, strnlen(buf.data() + at, width));
  }
  return out;
}

// Reads a text attribute or dataset of fixed-length strings through `reader`.
template <class Read>
std::vector<std::string> read_texts(hid_t file_type, std::uint64_t count, Read reader,
                                    const std::string& what) {
  if (H5Tget_class(file_type) != H5T_STRING || H5Tis_variable_str(file_type) > 0) {
    throw Error(what + " is not fixed-length text");
  }
  const std::size_t width = H5Tget_size(file_type);
  Id mem = text_type(width);
  check(H5Tset_strpad(mem.get(), H5T_STR_NULLPAD), what);
  std::vector<char> buf(count * width);
  check(reader(mem.get(), buf.data()), "read " + what);
  return unpack(buf, width);
}

}  // namespace

Id& Id::operator=(Id&& o) noexcept {
  if (this != &o) {
    reset();
    id_ = std::exchange(o.id_, H5I_INVALID_HID);
    close_ = o.close_;
  }
  return *this;
}

void Id::reset() {
  if (id_ >= 0 && close_) close_(id_);
  id_ = H5I_INVALID_HID;
}

Id own(hid_t id, Id::Closer close, const std::string& what) {
  if (id < 0) throw Error(what + ": " + hdf5_message());
  return Id(id, close);
}

void check(herr_t status, const std::string& what) {
  if (status < 0) throw Error(what + ": " + hdf5_message());
}

QuietErrors::QuietErrors() {
  H5Eget_auto2(H5E_DEFAULT, &func_, &data_);
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
}

QuietErrors::~QuietErrors() {
  H5Eset_auto2(H5E_DEFAULT, func_, data_);
}

Id create_file(const std::filesystem::path& path) {
  Id fapl = own(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, "file access properties");
  check(H5Pset_file_locking(fapl.get(), false, true), "file locking");
  return own(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.get()), H5Fclose,
             "create " + path.string());
}

Id open_file_read(const std::filesystem::path& path) {
  Id fapl = own(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, "file access properties");
  check(H5Pset_file_locking(fapl.get(), false, true), "file locking");
  return own(H5Fopen(path.c_str(), H5F_ACC_RDONLY, fapl.get()), H5Fclose, "open " + path.string());
}

void flush(hid_t file) {
  check(H5Fflush(file, H5F_SCOPE_LOCAL), "flush results file");
}

Id create_group(hid_t parent, const std::string& name) {
  Id gcpl = own(H5Pcreate(H5P_GROUP_CREATE), H5Pclose, "group properties");
  check(H5Pset_obj_track_times(gcpl.get(), false), "group properties");
  return own(H5Gcreate2(parent, name.c_str(), H5P_DEFAULT, gcpl.get(), H5P_DEFAULT), H5Gclose,
             "create group " + name);
}

Id open_group(hid_t parent, const std::string& name) {
  return own(H5Gopen2(parent, name.c_str(), H5P_DEFAULT), H5Gclose, "open group " + name);
}

Id open_dataset(hid_t parent, const std::string& name) {
  return own(H5Dopen2(parent, name.c_str(), H5P_DEFAULT), H5Dclose, "open dataset " + name);
}

bool has_link(hid_t parent, const std::string& name) {
  return H5Lexists(parent, name.c_str(), H5P_DEFAULT) > 0;
}

bool has_attribute(hid_t object, const std::string& name) {
  return H5Aexists(object, name.c_str()) > 0;
}

void write_attribute(hid_t object, const std::string& name, const std::string& text,
                     std::size_t bytes) {
  Id type = text_type(std::max(bytes, text.size() + 1));
  Id space = simple_space({});
  Id attr = attribute_for_write(object, name, type.get(), space.get());
  std::vector<char> buf(std::max(bytes, text.size() + 1), '\0');
  std::memcpy(buf.data(), text.data(), text.size());
  check(H5Awrite(attr.get(), type.get(), buf.data()), "write attribute " + name);
}

void write_attribute(hid_t object, const std::string& name, std::int64_t value) {
  Id space = simple_space({});
  Id attr = attribute_for_write(object, name, H5T_STD_I64LE, space.get());
  check(H5Awrite(attr.get(), H5T_NATIVE_INT64, &value), "write attribute " + name);
}

void write_attribute(hid_t object, const std::string& name, const std::vector<std::string>& list) {
  const std::size_t width = widest(list);
  Id type = text_type(width);
  Id space = simple_space({list.size()});
  Id attr = attribute_for_write(object, name, type.get(), space.get());
  check(H5Awrite(attr.get(), type.get(), pack(list, width).data()), "write attribute " + name);
}

void overwrite_attribute(hid_t object, const std::string& name, const std::string& text) {
  Id attr = own(H5Aopen(object, name.c_str(), H5P_DEFAULT), H5Aclose, "open attribute " + name);
  Id type = own(H5Aget_type(attr.get()), H5Tclose, "attribute type " + name);
  const std::size_t width = H5Tget_size(type.get());
  std::vector<char> buf(width, '\0');
  std::memcpy(buf.data(), text.data(), std::min(text.size(), width - 1));
  check(H5Awrite(attr.get(), type.get(), buf.data()), "write attribute " + name);
}

void overwrite_attribute(hid_t object, const std::string& name, std::int64_t value) {
  Id attr = own(H5Aopen(object, name.c_str(), H5P_DEFAULT), H5Aclose, "open attribute " + name);
  check(H5Awrite(attr.get(), H5T_NATIVE_INT64, &value), "write attribute " + name);
}

std::string read_text_attribute(hid_t object, const std::string& name) {
  const std::vector<std::string> list = read_text_list_attribute(object, name);
  if (list.size() != 1) throw Error("attribute " + name + " is not a single text");
  return list[0];
}

std::int64_t read_int_attribute(hid_t object, const std::string& name) {
  Id attr = own(H5Aopen(object, name.c_str(), H5P_DEFAULT), H5Aclose, "open attribute " + name);
  Id type = own(H5Aget_type(attr.get()), H5Tclose, "attribute type " + name);
  if (H5Tget_class(type.get()) != H5T_INTEGER)
    throw Error("attribute " + name + " is not an integer");
  std::int64_t value = 0;
  check(H5Aread(attr.get(), H5T_NATIVE_INT64, &value), "read attribute " + name);
  return value;
}

std::vector<std::string> read_text_list_attribute(hid_t object, const std::string& name) {
  Id attr = own(H5Aopen(object, name.c_str(), H5P_DEFAULT), H5Aclose, "open attribute " + name);
  Id type = own(H5Aget_type(attr.get()), H5Tclose, "attribute type " + name);
  Id space = own(H5Aget_space(attr.get()), H5Sclose, "attribute space " + name);
  const hssize_t count = H5Sget_simple_extent_npoints(space.get());
  return read_texts(
      type.get(), static_cast<std::uint64_t>(std::max<hssize_t>(count, 0)),
      [&](hid_t mem, void* buf) { return H5Aread(attr.get(), mem, buf); }, "attribute " + name);
}

Id dataset_properties(const std::vector<hsize_t>& chunk, bool compress) {
  Id dcpl = own(H5Pcreate(H5P_DATASET_CREATE), H5Pclose, "dataset properties");
  check(H5Pset_obj_track_times(dcpl.get(), false), "dataset properties");
  if (!chunk.empty()) {
    check(H5Pset_chunk(dcpl.get(), static_cast<int>(chunk.size()), chunk.data()), "chunk shape");
  }
  if (compress) {
    // Shuffle groups the bytes of equal significance: it is what lets
    // deflate find the redundancy in float64 fields.
    check(H5Pset_shuffle(dcpl.get()), "shuffle filter");
    check(H5Pset_deflate(dcpl.get(), kDeflateLevel), "deflate filter");
  }
  return dcpl;
}

void write_dataset(hid_t parent, const std::string& name, hid_t mem_type, const void* data,
                   const std::vector<hsize_t>& dims, bool compress) {
  const bool chunked = compress && element_count(dims) > 0;
  Id dcpl = dataset_properties(chunked ? dims : std::vector<hsize_t>{}, chunked);
  Id space = simple_space(dims);
  Id set = own(
      H5Dcreate2(parent, name.c_str(), mem_type, space.get(), H5P_DEFAULT, dcpl.get(), H5P_DEFAULT),
      H5Dclose, "create dataset " + name);
  if (element_count(dims) > 0) {
    check(H5Dwrite(set.get(), mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), "write " + name);
  }
}

void write_text_dataset(hid_t parent, const std::string& name,
                        const std::vector<std::string>& list) {
  const std::size_t width = widest(list);
  Id type = text_type(width);
  Id space = simple_space({list.size()});
  Id dcpl = dataset_properties({}, false);
  Id set = own(H5Dcreate2(parent, name.c_str(), type.get(), space.get(), H5P_DEFAULT, dcpl.get(),
                          H5P_DEFAULT),
               H5Dclose, "create dataset " + name);
  if (!list.empty()) {
    check(H5Dwrite(set.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, pack(list, width).data()),
          "write " + name);
  }
}

std::vector<hsize_t> dims_of(hid_t dataset) {
  Id space = own(H5Dget_space(dataset), H5Sclose, "dataset space");
  const int rank = H5Sget_simple_extent_ndims(space.get());
  if (rank < 0) throw Error("dataset space: " + hdf5_message());
  std::vector<hsize_t> dims(static_cast<std::size_t>(rank));
  H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
  return dims;
}

std::uint64_t element_count(const std::vector<hsize_t>& dims) {
  std::uint64_t n = 1;
  for (hsize_t d : dims) n *= d;
  return n;
}

void read_rows(hid_t dataset, hid_t mem_type, void* out, hsize_t first, hsize_t count) {
  std::vector<hsize_t> dims = dims_of(dataset);
  if (dims.empty()) {
    check(H5Dread(dataset, mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out), "read dataset");
    return;
  }
  if (first + count > dims[0]) throw Error("read past the end of a dataset");
  Id file_space = own(H5Dget_space(dataset), H5Sclose, "dataset space");
  std::vector<hsize_t> start(dims.size(), 0);
  start[0] = first;
  dims[0] = count;
  check(H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, start.data(), nullptr, dims.data(),
                            nullptr),
        "select rows");
  Id mem_space = simple_space(dims);
  check(H5Dread(dataset, mem_type, mem_space.get(), file_space.get(), H5P_DEFAULT, out),
        "read dataset");
}

std::vector<std::string> read_text_dataset(hid_t dataset) {
  Id type = own(H5Dget_type(dataset), H5Tclose, "dataset type");
  return read_texts(
      type.get(), element_count(dims_of(dataset)),
      [&](hid_t mem, void* buf) {
        return H5Dread(dataset, mem, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf);
      },
      "text dataset");
}

bool has_deflate(hid_t dataset) {
  Id dcpl = own(H5Dget_create_plist(dataset), H5Pclose, "dataset properties");
  const int n = H5Pget_nfilters(dcpl.get());
  for (int i = 0; i < n; ++i) {
    unsigned flags = 0;
    std::size_t nelem = 0;
    unsigned config = 0;
    if (H5Pget_filter2(dcpl.get(), static_cast<unsigned>(i), &flags, &nelem, nullptr, 0, nullptr,
                       &config) == H5Z_FILTER_DEFLATE) {
      return true;
    }
  }
  return false;
}

}  // namespace gearsph::results::h5
