#pragma once
// Conditional requests for the files the service serves (RFC 9110, 13):
// the validators of a file (a strong ETag and Last-Modified, 8.8) and the
// preconditions a download sends with them: If-None-Match and
// If-Modified-Since (304 Not Modified), If-Range (a range only of the same
// file).
#include <cstdint>
#include <ctime>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

namespace gearsph::server {

struct FileValidators {
  // Strong (8.8.3.1): the file's size and modification time in nanoseconds.
  // Result files are written whole and renamed into place (write_file_atomic,
  // the results writer), so a new content is a new ETag.
  std::string etag;
  std::string last_modified;  // IMF-fixdate (5.6.7)
  std::time_t modified = 0;   // seconds since 1970, for If-Modified-Since
};

// nullopt when the file cannot be examined.
std::optional<FileValidators> file_validators(const std::filesystem::path& file);

// IMF-fixdate: "Sun, 06 Nov 1994 08:49:37 GMT".
std::string http_date(std::time_t t);
// An IMF-fixdate; nullopt for anything else (the obsolete forms of 5.6.7
// included: a precondition that cannot be read is ignored, 13.1.3).
std::optional<std::time_t> parse_http_date(std::string_view s);

// If-None-Match (13.1.2): "*" or a list of entity tags, compared weakly.
bool none_match_fails(std::string_view if_none_match, const FileValidators& v);
// If-Modified-Since (13.1.3): the file is no newer than the date.
bool not_modified_since(std::string_view if_modified_since, const FileValidators& v);
// If-Range (13.1.5): a strong match of the entity tag, or the exact
// Last-Modified date. False: the Range is ignored, the whole file sent.
bool if_range_holds(std::string_view if_range, const FileValidators& v);

}  // namespace gearsph::server
