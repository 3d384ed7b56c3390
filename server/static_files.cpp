#include "server/static_files.hpp"

#include <algorithm>
#include <map>

#include "server/conditional_requests.hpp"
#include "server/problem.hpp"

namespace gearsph::server {

std::string content_type_for(const std::filesystem::path& file) {
  static const std::map<std::string, std::string> types = {
      {".html", "text/html; charset=utf-8"},
      {".htm", "text/html; charset=utf-8"},
      {".js", "text/javascript; charset=utf-8"},
      {".mjs", "text/javascript; charset=utf-8"},
      {".css", "text/css; charset=utf-8"},
      {".json", "application/json"},
      {".map", "application/json"},
      {".csv", "text/csv; charset=utf-8"},
      {".txt", "text/plain; charset=utf-8"},
      {".md", "text/markdown; charset=utf-8"},
      {".png", "image/png"},
      {".jpg", "image/jpeg"},
      {".svg", "image/svg+xml"},
      {".ico", "image/x-icon"},
      {".woff2", "font/woff2"},
      {".wasm", "application/wasm"},
      {".h5", "application/x-hdf5"},
      {".xmf", "application/xml"},
      {".xml", "application/xml"},
  };
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  const auto it = types.find(ext);
  return it == types.end() ? "application/octet-stream" : it->second;
}

bool is_plain_file_name(std::string_view name) {
  if (name.empty() || name.size() > 200 || name.front() == '.') return false;
  return std::all_of(name.begin(), name.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '.' ||
           c == '_' || c == '-' || c == '+';
  });
}

std::vector<FileEntry> list_files(const std::filesystem::path& dir) {
  std::vector<FileEntry> out;
  std::error_code ec;
  for (std::filesystem::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (!is_plain_file_name(name) || it->path().extension() == ".tmp") continue;
    std::error_code sec;
    // symlink_status: a link is never followed out of the directory.
    if (!std::filesystem::is_regular_file(it->symlink_status(sec)) || sec) continue;
    const auto bytes = it->file_size(sec);
    if (sec) continue;
    out.push_back({name, bytes});
  }
  std::sort(out.begin(), out.end(),
            [](const FileEntry& a, const FileEntry& b) { return a.name < b.name; });
  return out;
}

std::optional<std::filesystem::path> find_listed_file(const std::filesystem::path& dir,
                                                      std::string_view name) {
  if (!is_plain_file_name(name)) return std::nullopt;
  for (const FileEntry& f : list_files(dir)) {
    if (f.name == name) return dir / f.name;
  }
  return std::nullopt;
}

Response serve_file(const Request& req, const std::filesystem::path& file,
                    const std::string& content_type) {
  boost::beast::error_code ec;
  http::basic_file_body<RangeFile>::value_type body;
  body.open(file.c_str(), boost::beast::file_mode::scan, ec);
  if (ec) return problem::plain(http::status::not_found, "no such file", req.path);
  const std::uint64_t size = body.size();
  const std::optional<FileValidators> validators = file_validators(file);
  auto with_validators = [&](auto& res) {
    if (!validators) return;
    res.set(http::field::etag, validators->etag);
    res.set(http::field::last_modified, validators->last_modified);
  };
  // RFC 9110, 13.2.2: If-None-Match, else If-Modified-Since, then If-Range.
  if (validators) {
    const std::string none_match = req.header(http::field::if_none_match);
    const std::string since = req.header(http::field::if_modified_since);
    if (!none_match.empty() ? none_match_fails(none_match, *validators)
                            : !since.empty() && not_modified_since(since, *validators)) {
      StringResponse res{http::status::not_modified, 11};
      with_validators(res);
      res.set(http::field::accept_ranges, "bytes");
      return res;
    }
  }

  http::status status = http::status::ok;
  std::string content_range;
  const std::string range_header = req.header(http::field::range);
  const std::string if_range = req.header(http::field::if_range);
  // A range of another version of the file would be spliced into the wrong
  // bytes: without a match the whole file goes (13.1.5).
  const bool range_applies =
      if_range.empty() || (validators && if_range_holds(if_range, *validators));
  if (!range_header.empty() && range_applies) {
    ByteRange range;
    switch (parse_range(range_header, size, range)) {
      case RangeParse::unsatisfiable: {
        StringResponse res =
            problem::plain(http::status::range_not_satisfiable,
                           "the file has " + std::to_string(size) + " bytes", req.path);
        res.set(http::field::content_range, "bytes */" + std::to_string(size));
        return res;
      }
      case RangeParse::ok: {
        RangeFile f = std::move(body.file());
        f.restrict(range.first, range.length(), ec);
        if (ec) return problem::plain(http::status::internal_server_error, ec.message(), req.path);
        body.reset(std::move(f), ec);
        if (ec) return problem::plain(http::status::internal_server_error, ec.message(), req.path);
        status = http::status::partial_content;
        content_range = "bytes " + std::to_string(range.first) + "-" + std::to_string(range.last) +
                        "/" + std::to_string(size);
        break;
      }
      case RangeParse::none:
        break;
    }
  }
  FileResponse res{status, 11};
  res.body() = std::move(body);
  res.set(http::field::content_type, content_type);
  res.set(http::field::accept_ranges, "bytes");
  with_validators(res);
  if (!content_range.empty()) res.set(http::field::content_range, content_range);
  res.prepare_payload();
  return res;
}

std::optional<std::filesystem::path> find_static(const Request& req,
                                                 const std::filesystem::path& root) {
  if (root.empty()) return std::nullopt;
  std::filesystem::path file = root;
  for (std::size_t i = 0; i < req.segments.size(); ++i) {
    const std::string& s = req.segments[i];
    if (s.empty() && i + 1 == req.segments.size()) break;  // trailing slash: the index
    if (!is_plain_file_name(s)) return std::nullopt;
    file /= s;
  }
  std::error_code ec;
  if (std::filesystem::is_directory(file, ec)) file /= "index.html";
  if (!std::filesystem::is_regular_file(file, ec)) return std::nullopt;
  // A symbolic link inside the web root must not lead out of it.
  const auto real_root = std::filesystem::canonical(root, ec);
  if (ec) return std::nullopt;
  const auto real_file = std::filesystem::canonical(file, ec);
  if (ec) return std::nullopt;
  const auto rel = real_file.lexically_relative(real_root);
  if (rel.empty() || *rel.begin() == "..") return std::nullopt;
  return real_file;
}

std::optional<Response> serve_static(const Request& req, const std::filesystem::path& root) {
  const auto file = find_static(req, root);
  if (!file) return std::nullopt;
  Response res = serve_file(req, *file, content_type_for(*file));
  if (auto* f = std::get_if<FileResponse>(&res)) f->set(http::field::cache_control, "no-cache");
  return res;
}

}  // namespace gearsph::server
