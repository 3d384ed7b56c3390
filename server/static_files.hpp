#pragma once
// Files on disk as HTTP answers: the dashboard's static files and the files
// of a job directory. Only plain names that a directory listing shows are
// ever opened, so no request reaches outside its directory.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "server/http_types.hpp"

namespace gearsph::server {

std::string content_type_for(const std::filesystem::path& file);

// [A-Za-z0-9._+-]+, at most 200 characters, not starting with '.'.
bool is_plain_file_name(std::string_view name);

struct FileEntry {
  std::string name;
  std::uint64_t bytes = 0;
};
// Regular files (not symbolic links, not hidden, not *.tmp being written) in dir, sorted.
std::vector<FileEntry> list_files(const std::filesystem::path& dir);
// `name` if it is one of list_files(dir).
std::optional<std::filesystem::path> find_listed_file(const std::filesystem::path& dir,
                                                      std::string_view name);

// 200 with the whole file, 206 with one requested range, 416 for a range
// past the end; the body is streamed from disk.
Response serve_file(const Request& req, const std::filesystem::path& file,
                    const std::string& content_type);

// The dashboard: "/" is index.html, other paths are files under root.
// nullopt if there is no such file (the caller answers 404).
std::optional<Response> serve_static(const Request& req, const std::filesystem::path& root);
// The file serve_static would serve (inside root, links resolved).
std::optional<std::filesystem::path> find_static(const Request& req,
                                                 const std::filesystem::path& root);

}  // namespace gearsph::server
