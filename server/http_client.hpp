#pragma once
// A small synchronous HTTP/1.1 client (Beast) for `gearsph submit`, the
// tests and the load benchmark: requests over a kept-alive connection,
// downloads streamed to a file, Server-Sent Events read as they arrive.
#include <chrono>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

namespace gearsph::server {

struct ClientResponse {
  unsigned status = 0;
  std::map<std::string, std::string> headers;  // names in lower case
  std::string body;
  std::string header(const std::string& name) const;  // "" if absent (case-insensitive)
  nlohmann::json json() const;                        // throws if the body is not JSON
};

struct SseEvent {
  std::string id, event, data;
};

struct Url {
  std::string host, port;
  std::string base;  // the path before the API's own ("/api" behind a proxy), no trailing '/'
  // http://host[:port][/base][/]; throws otherwise.
  static Url parse(const std::string& url);
  // "http://host:port" + base: what the API's paths follow.
  std::string root() const;
};

class HttpClient {
 public:
  using Headers = std::vector<std::pair<std::string, std::string>>;

  HttpClient(std::string host, std::string port,
             std::chrono::milliseconds timeout = std::chrono::seconds(30));
  ~HttpClient();
  HttpClient(const HttpClient&) = delete;
  HttpClient& operator=(const HttpClient&) = delete;

  // Sent with every request (e.g. Authorization).
  void set_default_header(std::string name, std::string value);

  // Any method, including made-up ones. Reuses the connection while the
  // server keeps it alive; reconnects once if a reused one was closed.
  ClientResponse request(std::string_view method, const std::string& target,
                         const std::string& body = "", const Headers& headers = {});
  ClientResponse get(const std::string& target, const Headers& headers = {}) {
    return request("GET", target, "", headers);
  }
  ClientResponse post_json(const std::string& target, const std::string& body,
                           Headers headers = {});

  // GET into `file` when the answer is 200/206 (the body is left empty);
  // otherwise the answer is returned as usual and no file is written.
  ClientResponse download(const std::string& target, const std::filesystem::path& file,
                          const Headers& headers = {});

  // Reads an event stream until on_event returns false, the server ends the
  // stream, or nothing (not even a keep-alive) arrives within the timeout.
  // Returns the response head (status and headers; body empty if the stream opened).
  ClientResponse events(const std::string& target,
                        const std::function<bool(const SseEvent&)>& on_event,
                        const Headers& headers = {});

  void close();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  Headers defaults_;
};

// Bytes to a fresh connection and whatever comes back until the server
// closes it or the timeout passes: for malformed requests.
std::string raw_exchange(const std::string& host, const std::string& port, const std::string& bytes,
                         std::chrono::milliseconds timeout, bool half_close = true);

}  // namespace gearsph::server
