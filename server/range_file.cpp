#include "server/range_file.hpp"

#include <cctype>
#include <charconv>
#include <limits>

namespace gearsph::server {

void RangeFile::open(const char* path, boost::beast::file_mode mode, boost::beast::error_code& ec) {
  length_.reset();
  file_.open(path, mode, ec);
}

void RangeFile::restrict(std::uint64_t first, std::uint64_t length, boost::beast::error_code& ec) {
  file_.seek(first, ec);
  if (!ec) length_ = length;
}

std::uint64_t RangeFile::size(boost::beast::error_code& ec) const {
  if (length_) {
    ec = {};
    return *length_;
  }
  return file_.size(ec);
}

namespace {

// 1*DIGIT (RFC 9110, 14.1.1: first-pos, last-pos, suffix-length): nothing
// else, no sign, no space. A value past 2^64 is still a position: max().
std::optional<std::uint64_t> digits(std::string_view s) {
  if (s.empty()) return std::nullopt;
  for (char c : s) {
    if (c < '0' || c > '9') return std::nullopt;
  }
  std::uint64_t v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec == std::errc::result_out_of_range) return std::numeric_limits<std::uint64_t>::max();
  if (ec != std::errc() || end != s.data() + s.size()) return std::nullopt;
  return v;
}

bool equals_ignoring_case(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (std::tolower(static_cast<unsigned char>(a[i])) !=
        std::tolower(static_cast<unsigned char>(b[i]))) {
      return false;
    }
  }
  return true;
}

}  // namespace

RangeParse parse_range(std::string_view header, std::uint64_t size, ByteRange& out) {
  // ranges-specifier = range-unit "=" range-set; the unit is case-insensitive (14.1).
  const auto equals = header.find('=');
  if (equals == std::string_view::npos ||
      !equals_ignoring_case(header.substr(0, equals), "bytes")) {
    return RangeParse::none;
  }
  const std::string_view spec = header.substr(equals + 1);
  // Several ranges: the whole file, which a server may send instead (14.2).
  if (spec.find(',') != std::string_view::npos) return RangeParse::none;
  const auto dash = spec.find('-');
  if (dash == std::string_view::npos) return RangeParse::none;
  const std::string_view a = spec.substr(0, dash), b = spec.substr(dash + 1);
  if (a.empty()) {
    // suffix-range = "-" suffix-length: the last n bytes (14.1.2).
    const auto n = digits(b);
    if (!n) return RangeParse::none;
    if (*n == 0 || size == 0) return RangeParse::unsatisfiable;
    out.first = *n >= size ? 0 : size - *n;
    out.last = size - 1;
    return RangeParse::ok;
  }
  // int-range = first-pos "-" [ last-pos ]
  const auto first = digits(a);
  if (!first) return RangeParse::none;
  std::optional<std::uint64_t> last;
  if (!b.empty()) {
    last = digits(b);
    if (!last) return RangeParse::none;
    // last < first is invalid, and an invalid range-set is ignored (14.2).
    if (*last < *first) return RangeParse::none;
  }
  if (*first >= size) return RangeParse::unsatisfiable;
  out.first = *first;
  out.last = last && *last < size ? *last : size - 1;
  return RangeParse::ok;
}

}  // namespace gearsph::server
