#pragma once
// What a handler sees and returns: a parsed request (percent-decoded path
// segments, query parameters, route parameters) and one of three responses:
// a string body, a streamed file, or the start of an event stream.
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

#include <boost/beast/http.hpp>
#include <nlohmann/json.hpp>

#include "server/range_file.hpp"

namespace gearsph::server {

namespace http = boost::beast::http;

using StringResponse = http::response<http::string_body>;
using FileResponse = http::response<http::basic_file_body<RangeFile>>;

// GET .../events: the session keeps the connection and streams events.
struct EventStream {
  http::response<http::empty_body> head;
  std::string job_id;                          // empty: every job
  std::optional<std::uint64_t> last_event_id;  // from the Last-Event-ID header
  std::uint64_t after = 0;                     // stream the hub's events after this id
  std::string first;                           // sent before them (a status snapshot, a reset)
  bool final = false;                          // `first` is the job's final status: then end
};

using Response = std::variant<StringResponse, FileResponse, EventStream>;

struct Request {
  http::request<http::string_body> msg;
  std::string path;                                        // as received, without the query
  std::vector<std::string> segments;                       // percent-decoded path segments
  std::vector<std::pair<std::string, std::string>> query;  // decoded, in order
  std::map<std::string, std::string> params;               // {name} parts of the route
  // Whether the client has closed its connection while the handler runs
  // (off the I/O threads); a handler doing long work stops then. Empty: never.
  std::function<bool()> gone;
  // The client's address (the peer of the connection): failed logins and
  // queue quotas are counted by it. "" when not known.
  std::string client;

  std::string header(http::field f) const { return std::string(msg[f]); }
  std::optional<std::string> query_value(std::string_view name) const;
  std::vector<std::string> query_values(std::string_view name) const;
  const std::string& param(const std::string& name) const { return params.at(name); }
};

// Splits the request target into path, segments and query; false if it is
// not an origin-form target or holds invalid percent-encoding.
bool parse_target(std::string_view target, Request& out);
std::optional<std::string> percent_decode(std::string_view s, bool plus_is_space);
std::string percent_encode(std::string_view s);  // for query values in links

// A browser's page load (Accept: text/html, or ?f=html) rather than a
// program (*/*, JSON, or ?f=json).
bool wants_html(const Request& req);

StringResponse text_response(http::status status, std::string body, std::string content_type);
StringResponse json_response(http::status status, const nlohmann::json& body);

unsigned status_code(const Response& r);

}  // namespace gearsph::server
