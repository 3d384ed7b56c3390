#pragma once
// A Beast File that exposes one byte range of a file, so http::basic_file_body
// streams "206 Partial Content" answers the same way it streams whole files.
// Plus the parsing of a single-range "Range: bytes=..." header (RFC 9110 14.1).
#include <cstdint>
#include <optional>
#include <string_view>

#include <boost/beast/core/file.hpp>

namespace gearsph::server {

class RangeFile {
 public:
  RangeFile() = default;
  RangeFile(RangeFile&&) = default;
  RangeFile& operator=(RangeFile&&) = default;

  // Opens `path` for reading, whole.
  void open(const char* path, boost::beast::file_mode mode, boost::beast::error_code& ec);
  // Narrows to [first, first + length); the next read starts at `first`.
  void restrict(std::uint64_t first, std::uint64_t length, boost::beast::error_code& ec);

  bool is_open() const { return file_.is_open(); }
  void close(boost::beast::error_code& ec) { file_.close(ec); }
  // The size of the range, which is what the body sends.
  std::uint64_t size(boost::beast::error_code& ec) const;
  std::uint64_t file_size(boost::beast::error_code& ec) const { return file_.size(ec); }
  std::uint64_t pos(boost::beast::error_code& ec) { return file_.pos(ec); }
  void seek(std::uint64_t offset, boost::beast::error_code& ec) { file_.seek(offset, ec); }
  std::size_t read(void* buffer, std::size_t n, boost::beast::error_code& ec) {
    return file_.read(buffer, n, ec);
  }
  std::size_t write(const void* buffer, std::size_t n, boost::beast::error_code& ec) {
    return file_.write(buffer, n, ec);
  }

 private:
  boost::beast::file file_;
  std::optional<std::uint64_t> length_;
};

struct ByteRange {
  std::uint64_t first = 0, last = 0;  // inclusive
  std::uint64_t length() const { return last - first + 1; }
};

enum class RangeParse { none, ok, unsatisfiable };

// "bytes=a-b", "bytes=a-" or "bytes=-n" against a file of `size` bytes,
// positions digits only (RFC 9110, 14.1.2). Several ranges, other units or
// anything malformed ("bytes=1e2-200", "bytes= 1-2") give `none`: the
// header is ignored and the whole file sent (14.2); a range starting past
// the end, or "-0", gives `unsatisfiable` (416, 15.5.17).
RangeParse parse_range(std::string_view header, std::uint64_t size, ByteRange& out);

}  // namespace gearsph::server
