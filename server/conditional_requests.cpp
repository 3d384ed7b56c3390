#include "server/conditional_requests.hpp"

#include <sys/stat.h>

#include <cstdio>

namespace gearsph::server {

namespace {

std::string_view trimmed(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

// The opaque tag of an entity tag, without "W/" (the weak comparison, 8.8.3.2).
std::string_view opaque(std::string_view tag) {
  if (tag.substr(0, 2) == "W/") tag.remove_prefix(2);
  return tag;
}

}  // namespace

std::optional<FileValidators> file_validators(const std::filesystem::path& file) {
  struct stat st {};
  if (::stat(file.c_str(), &st) != 0) return std::nullopt;
  FileValidators v;
  const auto ns = static_cast<unsigned long long>(st.st_mtim.tv_sec) * 1000000000ull +
                  static_cast<unsigned long long>(st.st_mtim.tv_nsec);
  char tag[64];
  std::snprintf(tag, sizeof tag, "\"%llx-%llx\"", static_cast<unsigned long long>(st.st_size), ns);
  v.etag = tag;
  v.modified = st.st_mtim.tv_sec;
  v.last_modified = http_date(v.modified);
  return v;
}

std::string http_date(std::time_t t) {
  std::tm tm{};
  ::gmtime_r(&t, &tm);
  char out[40];
  // The names are English whatever the locale (5.6.7).
  static const char* const days[] = {"Sun", "Mon", "Tue", "Wed", "Thu", "Fri", "Sat"};
  static const char* const months[] = {"Jan", "Feb", "Mar", "Apr", "May", "Jun",
                                       "Jul", "Aug", "Sep", "Oct", "Nov", "Dec"};
  std::snprintf(out, sizeof out, "%s, %02d %s %04d %02d:%02d:%02d GMT", days[tm.tm_wday],
                tm.tm_mday, months[tm.tm_mon], tm.tm_year + 1900, tm.tm_hour, tm.tm_min, tm.tm_sec);
  return out;
}

std::optional<std::time_t> parse_http_date(std::string_view s) {
  s = trimmed(s);
  if (s.size() != 29) return std::nullopt;
  int day = 0, year = 0, hour = 0, minute = 0, second = 0;
  char weekday[4] = {}, month[4] = {}, zone[4] = {};
  const std::string text(s);
  int used = 0;
  if (std::sscanf(text.c_str(), "%3c, %2d %3c %4d %2d:%2d:%2d %3c%n", weekday, &day, month, &year,
                  &hour, &minute, &second, zone, &used) != 8 ||
      used != 29 || std::string_view(zone, 3) != "GMT") {
    return std::nullopt;
  }
  static const char* const months[] = {"Jan", "Feb", "Mar", "Apr", "May", "Jun",
                                       "Jul", "Aug", "Sep", "Oct", "Nov", "Dec"};
  int m = -1;
  for (int i = 0; i < 12; ++i) {
    if (std::string_view(month, 3) == months[i]) m = i;
  }
  if (m < 0 || day < 1 || day > 31 || hour > 23 || minute > 59 || second > 60) return std::nullopt;
  std::tm tm{};
  tm.tm_year = year - 1900;
  tm.tm_mon = m;
  tm.tm_mday = day;
  tm.tm_hour = hour;
  tm.tm_min = minute;
  tm.tm_sec = second;
  return ::timegm(&tm);
}

bool none_match_fails(std::string_view header, const FileValidators& v) {
  header = trimmed(header);
  if (header == "*") return true;
  while (!header.empty()) {
    const auto comma = header.find(',');
    const std::string_view tag = trimmed(header.substr(0, comma));
    if (!tag.empty() && opaque(tag) == opaque(v.etag)) return true;
    if (comma == std::string_view::npos) break;
    header.remove_prefix(comma + 1);
  }
  return false;
}

bool not_modified_since(std::string_view header, const FileValidators& v) {
  const auto since = parse_http_date(header);
  return since && v.modified <= *since;
}

bool if_range_holds(std::string_view header, const FileValidators& v) {
  header = trimmed(header);
  // An entity tag: the strong comparison, so a weak tag never matches (8.8.3.2).
  if (!header.empty() && (header.front() == '"' || header.substr(0, 2) == "W/")) {
    return header == v.etag;
  }
  return header == v.last_modified;
}

}  // namespace gearsph::server
