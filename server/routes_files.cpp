// A job's files, and images rendered from its results on request.
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>

#include "server/problem.hpp"
#include "server/routes.hpp"
#include "server/static_files.hpp"

namespace gearsph::server::routes {

namespace {

std::optional<JobRecord> find_job(Services& s, const Request& req) {
  if (!is_id(req.param("id"))) return std::nullopt;
  return s.store.job(req.param("id"));
}

// A dismissed job's files are deleted (once its run has stopped): none is
// listed or served meanwhile.
StringResponse dismissed(const Request& req, const JobRecord& job) {
  return problem::plain(http::status::not_found,
                        "job " + job.id + " was dismissed; its files are deleted", req.path);
}

bool is_field_name(std::string_view f) {
  return !f.empty() && f.size() <= 64 && std::all_of(f.begin(), f.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
  });
}

std::optional<double> finite_number(std::string_view s) {
  // std::from_chars for double is in GCC 11+ libstdc++.
  double v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || end != s.data() + s.size() || !std::isfinite(v)) return std::nullopt;
  return v;
}

std::string short_number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

// Round-trips: the shortest text that reads back as v.
std::string exact_number(double v) {
  char buf[32];
  const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v);
  return ec == std::errc() ? std::string(buf, end) : short_number(v);
}

}  // namespace

Response files(Services& s, Request& req) {
  const auto record = find_job(s, req);
  if (!record) return problem::no_such_job(req);
  if (record->status == JobStatus::dismissed) return dismissed(req, *record);
  nlohmann::json list = nlohmann::json::array();
  for (const FileEntry& f : list_files(s.job_dir(*record))) {
    list.push_back({{"name", f.name},
                    {"bytes", f.bytes},
                    {"type", content_type_for(f.name)},
                    {"href", "/jobs/" + record->id + "/files/" + f.name}});
  }
  return json_response(http::status::ok, {{"jobID", record->id}, {"files", list}});
}

Response file(Services& s, Request& req) {
  const auto record = find_job(s, req);
  if (!record) return problem::no_such_job(req);
  if (record->status == JobStatus::dismissed) return dismissed(req, *record);
  const std::string& name = req.param("name");
  // Only a name the directory listing shows: no "..", no "/", no links.
  const auto path = find_listed_file(s.job_dir(*record), name);
  if (!path) {
    return problem::plain(http::status::not_found,
                          "job " + record->id + " has no file named \"" + name + "\"", req.path);
  }
  Response res = serve_file(req, *path, content_type_for(*path));
  // Results do not change once written; a running job's files may.
  if (auto* f = std::get_if<FileResponse>(&res); f && record->status == JobStatus::successful) {
    f->set(http::field::cache_control, "private, max-age=3600");
  }
  return res;
}

Response image(Services& s, Request& req) {
  const auto record = find_job(s, req);
  if (!record) return problem::no_such_job(req);
  const std::string& image = req.param("image");
  const std::string suffix = ".png";
  if (image.size() <= suffix.size() ||
      image.compare(image.size() - suffix.size(), suffix.size(), suffix) != 0 ||
      !is_field_name(image.substr(0, image.size() - suffix.size()))) {
    return problem::plain(http::status::not_found,
                          "images are named {field}.png, the field in letters, digits and _",
                          req.path);
  }
  ImageRequest ir;
  ir.field = image.substr(0, image.size() - suffix.size());
  std::string cache = record->id + "/" + ir.field;
  if (auto f = req.query_value("frame")) {
    std::int64_t frame = -1;
    const auto [end, ec] = std::from_chars(f->data(), f->data() + f->size(), frame);
    if (ec != std::errc() || end != f->data() + f->size() || frame < 0) {
      return problem::invalid_parameter(req, "frame is a whole number, 0 or more");
    }
    ir.frame = frame;
    cache += "?frame=" + std::to_string(frame);
  } else {
    cache += "?last";
  }
  if (auto z = req.query_value("zoom")) {
    std::array<double, 4> box{};
    std::size_t start = 0;
    int n = 0;
    bool ok = true;
    for (; n < 4 && ok; ++n) {
      const auto comma = z->find(',', start);
      if ((n < 3) != (comma != std::string::npos)) ok = false;
      const auto v = finite_number(std::string_view(*z).substr(start, comma - start));
      if (!v) ok = false;
      if (ok) box[static_cast<std::size_t>(n)] = *v;
      start = comma + 1;
    }
    if (!ok || !(box[0] < box[2]) || !(box[1] < box[3])) {
      return problem::invalid_parameter(req,
                                        "zoom is x0,y0,x1,y1 in metres with x0 < x1 and y0 < y1");
    }
    ir.zoom_m = box;
    cache += "&zoom=" + short_number(box[0]) + "," + short_number(box[1]) + "," +
             short_number(box[2]) + "," + short_number(box[3]);
  }
  if (auto r = req.query_value("range")) {
    const auto comma = r->find(',');
    const auto lo = finite_number(std::string_view(*r).substr(0, comma));
    const auto hi = comma == std::string::npos
                        ? std::nullopt
                        : finite_number(std::string_view(*r).substr(comma + 1));
    if (!lo || !hi || !(*lo < *hi)) {
      return problem::invalid_parameter(req, "range is lo,hi in the field's SI unit with lo < hi");
    }
    ir.range = std::array<double, 2>{*lo, *hi};
    // Full precision: two ranges that differ are two images.
    cache += "&range=" + exact_number(*lo) + "," + exact_number(*hi);
  }

  if (!s.config.image_provider) {
    problem::Problem p;
    p.status = http::status::not_implemented;
    p.type = problem::kRenderingUnavailable;
    p.title = "Rendering not available";
    p.detail = "rendering not available in this build";
    p.instance = req.path;
    return problem::make(p);
  }
  if (record->status != JobStatus::successful) {
    problem::Problem p;
    p.status = http::status::not_found;
    p.type = problem::kResultNotReady;
    p.title = "Result not ready";
    p.detail = "images are rendered from the results of a successful job; this one is " +
               std::string(to_string(record->status));
    p.instance = req.path;
    return problem::make(p);
  }
  // A finished job's results do not change: neither do its images.
  auto answer = [](const std::string& png) {
    StringResponse res = text_response(http::status::ok, png, "image/png");
    res.set(http::field::cache_control, "private, max-age=3600");
    return res;
  };
  if (const auto cached = s.images.get(cache)) return answer(*cached);
  ImageResult r = s.config.image_provider(s.job_dir(*record), ir);
  if (r.status != 200) {
    const bool error_status = r.status >= 400 && r.status <= 599;
    return problem::plain(
        error_status ? static_cast<http::status>(r.status) : http::status::internal_server_error,
        r.detail.empty() ? "the image could not be rendered" : r.detail, req.path);
  }
  StringResponse res = answer(r.png);
  s.images.put(cache, std::move(r.png));
  return res;
}

}  // namespace gearsph::server::routes
