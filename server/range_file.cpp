#include "server/range_file.hpp"

#include <charconv>

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

std::optional<std::uint64_t> number(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  if (s.empty()) return std::nullopt;
  std::uint64_t v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || end != s.data() + s.size()) return std::nullopt;
  return v;
}

}  // namespace

RangeParse parse_range(std::string_view header, std::uint64_t size, ByteRange& out) {
  constexpr std::string_view unit = "bytes=";
  if (header.substr(0, unit.size()) != unit) return RangeParse::none;
  const std::string_view spec = header.substr(unit.size());
  if (spec.find(',') != std::string_view::npos) return RangeParse::none;
  const auto dash = spec.find('-');
  if (dash == std::string_view::npos) return RangeParse::none;
  const std::string_view a = spec.substr(0, dash), b = spec.substr(dash + 1);
  const auto first = number(a), last = number(b);
  if (!first) {
    // Suffix range: the last n bytes.
    if (!last) return RangeParse::none;
    if (*last == 0 || size == 0) return RangeParse::unsatisfiable;
    out.first = *last >= size ? 0 : size - *last;
    out.last = size - 1;
    return RangeParse::ok;
  }
  if (!b.empty() && !last) return RangeParse::none;
  if (last && *last < *first) return RangeParse::none;
  if (*first >= size) return RangeParse::unsatisfiable;
  out.first = *first;
  out.last = last && *last < size ? *last : size - 1;
  return RangeParse::ok;
}

}  // namespace gearsph::server
