#include "server/http_client.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>

#include <boost/asio/connect.hpp>
#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/write.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>

namespace gearsph::server {

namespace beast = boost::beast;
namespace http = beast::http;
namespace net = boost::asio;
using tcp = net::ip::tcp;

namespace {

// Beast 1.74 compares a body_limit of boost::none as smaller than any length.
constexpr std::uint64_t kNoLimit = std::numeric_limits<std::uint64_t>::max();

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

template <class Fields>
void copy_headers(const Fields& from, ClientResponse& to) {
  for (const auto& f : from)
    to.headers[lower(std::string(f.name_string()))] = std::string(f.value());
}

// Drains the events complete in `buffer` (blank-line separated) into `out`.
void take_events(std::string& buffer, std::vector<SseEvent>& out) {
  std::size_t start = 0;
  for (;;) {
    const auto end = buffer.find("\n\n", start);
    if (end == std::string::npos) break;
    SseEvent e;
    bool any = false;
    std::size_t line_start = start;
    while (line_start < end) {
      auto line_end = buffer.find('\n', line_start);
      if (line_end == std::string::npos || line_end > end) line_end = end;
      std::string line = buffer.substr(line_start, line_end - line_start);
      if (!line.empty() && line.back() == '\r') line.pop_back();
      line_start = line_end + 1;
      if (line.empty() || line.front() == ':') continue;  // comment / keep-alive
      const auto colon = line.find(':');
      const std::string field = line.substr(0, colon);
      std::string value = colon == std::string::npos ? "" : line.substr(colon + 1);
      if (!value.empty() && value.front() == ' ') value.erase(0, 1);
      if (field == "data") {
        e.data += (e.data.empty() ? "" : "\n") + value;
        any = true;
      } else if (field == "event") {
        e.event = value;
        any = true;
      } else if (field == "id") {
        e.id = value;
        any = true;
      }
    }
    if (any && (!e.data.empty() || !e.event.empty())) {
      if (e.event.empty()) e.event = "message";
      out.push_back(std::move(e));
    }
    start = end + 2;
  }
  buffer.erase(0, start);
}

}  // namespace

std::string ClientResponse::header(const std::string& name) const {
  const auto it = headers.find(lower(name));
  return it == headers.end() ? std::string() : it->second;
}

nlohmann::json ClientResponse::json() const {
  return nlohmann::json::parse(body);
}

Url Url::parse(const std::string& url) {
  const std::string scheme = "http://";
  if (url.rfind(scheme, 0) != 0) {
    throw std::invalid_argument("the server URL must start with http:// (got '" + url + "')");
  }
  std::string rest = url.substr(scheme.size());
  const auto slash = rest.find('/');
  std::string path = slash == std::string::npos ? "" : rest.substr(slash);
  rest = rest.substr(0, slash);
  if (path.find_first_of("?#") != std::string::npos) {
    throw std::invalid_argument("the server URL has no query or fragment (got '" + url + "')");
  }
  while (!path.empty() && path.back() == '/') path.pop_back();
  Url u;
  u.base = path;
  if (!rest.empty() && rest.front() == '[') {  // [IPv6]:port
    const auto close = rest.find(']');
    if (close == std::string::npos) throw std::invalid_argument("bad server URL '" + url + "'");
    u.host = rest.substr(1, close - 1);
    u.port = close + 1 < rest.size() && rest[close + 1] == ':' ? rest.substr(close + 2) : "80";
  } else {
    const auto colon = rest.find(':');
    u.host = rest.substr(0, colon);
    u.port = colon == std::string::npos ? "80" : rest.substr(colon + 1);
  }
  if (u.host.empty() || u.port.empty()) throw std::invalid_argument("bad server URL '" + url + "'");
  return u;
}

std::string Url::root() const {
  const bool v6 = host.find(':') != std::string::npos;
  return "http://" + (v6 ? "[" + host + "]" : host) + ":" + port + base;
}

struct HttpClient::Impl {
  Impl(std::string h, std::string p, std::chrono::milliseconds t)
      : host(std::move(h)), port(std::move(p)), timeout(t), resolver(ioc) {}

  std::string host, port;
  std::chrono::milliseconds timeout;
  net::io_context ioc;
  tcp::resolver resolver;
  std::optional<beast::tcp_stream> stream;
  beast::flat_buffer buffer;

  // Runs the asynchronous operations started by `start` to completion: the
  // stream's timeouts only apply to asynchronous operations.
  template <class Start>
  beast::error_code run(Start start) {
    beast::error_code result = net::error::would_block;
    start([&result](beast::error_code ec, auto&&...) { result = ec; });
    ioc.restart();
    ioc.run();
    return result;
  }

  void connect() {
    close();
    const auto endpoints = resolver.resolve(host, port);
    stream.emplace(ioc);
    stream->expires_after(timeout);
    const auto ec = run([&](auto handler) { stream->async_connect(endpoints, handler); });
    if (ec) {
      stream.reset();
      throw std::runtime_error("cannot connect to " + host + ":" + port + ": " + ec.message());
    }
    buffer.clear();
  }

  void close() {
    if (stream) {
      beast::error_code ec;
      stream->socket().shutdown(tcp::socket::shutdown_both, ec);
      stream->close();
      stream.reset();
    }
    buffer.clear();
  }

  http::request<http::string_body> make(std::string_view method, const std::string& target,
                                        const std::string& body, const Headers& headers) {
    http::request<http::string_body> req;
    const http::verb v = http::string_to_verb(method);
    if (v == http::verb::unknown) {
      req.method_string(method);
    } else {
      req.method(v);
    }
    req.target(target);
    req.version(11);
    const bool v6 = host.find(':') != std::string::npos;
    req.set(http::field::host, (v6 ? "[" + host + "]" : host) + ":" + port);
    req.set(http::field::user_agent, "gearsph-client");
    for (const auto& [name, value] : headers) req.set(name, value);
    req.body() = body;
    if (!body.empty() || v == http::verb::post || v == http::verb::put) req.prepare_payload();
    return req;
  }

  beast::error_code send(http::request<http::string_body>& req) {
    stream->expires_after(timeout);
    return run([&](auto handler) { http::async_write(*stream, req, handler); });
  }
};

HttpClient::HttpClient(std::string host, std::string port, std::chrono::milliseconds timeout)
    : impl_(std::make_unique<Impl>(std::move(host), std::move(port), timeout)) {}

HttpClient::~HttpClient() = default;

void HttpClient::set_default_header(std::string name, std::string value) {
  defaults_.emplace_back(std::move(name), std::move(value));
}

void HttpClient::close() {
  impl_->close();
}

ClientResponse HttpClient::request(std::string_view method, const std::string& target,
                                   const std::string& body, const Headers& headers) {
  Headers all = defaults_;
  all.insert(all.end(), headers.begin(), headers.end());
  for (int attempt = 0;; ++attempt) {
    const bool reused = impl_->stream.has_value();
    if (!reused) impl_->connect();
    auto req = impl_->make(method, target, body, all);
    beast::error_code ec = impl_->send(req);
    http::response_parser<http::string_body> parser;
    parser.body_limit(kNoLimit);
    if (req.method() == http::verb::head) parser.skip(true);
    if (!ec) {
      impl_->stream->expires_after(impl_->timeout);
      ec = impl_->run(
          [&](auto handler) { http::async_read(*impl_->stream, impl_->buffer, parser, handler); });
    }
    if (ec) {
      impl_->close();
      // A kept-alive connection the server had closed meanwhile: once more on a new one.
      if (reused && attempt == 0 && ec != beast::error::timeout) continue;
      throw std::runtime_error(std::string(method) + " " + target + ": " + ec.message());
    }
    auto res = parser.release();
    ClientResponse out;
    out.status = res.result_int();
    copy_headers(res, out);
    out.body = std::move(res.body());
    if (!res.keep_alive()) impl_->close();
    return out;
  }
}

ClientResponse HttpClient::post_json(const std::string& target, const std::string& body,
                                     Headers headers) {
  headers.emplace_back("Content-Type", "application/json");
  return request("POST", target, body, headers);
}

ClientResponse HttpClient::download(const std::string& target, const std::filesystem::path& file,
                                    const Headers& headers) {
  Headers all = defaults_;
  all.insert(all.end(), headers.begin(), headers.end());
  impl_->connect();
  auto req = impl_->make("GET", target, "", all);
  if (auto ec = impl_->send(req)) {
    impl_->close();
    throw std::runtime_error("GET " + target + ": " + ec.message());
  }
  auto fail = [&](beast::error_code ec) {
    impl_->close();
    throw std::runtime_error("GET " + target + ": " + ec.message());
  };
  http::response_parser<http::empty_body> head;
  head.body_limit(kNoLimit);
  impl_->stream->expires_after(impl_->timeout);
  if (auto ec = impl_->run([&](auto handler) {
        http::async_read_header(*impl_->stream, impl_->buffer, head, handler);
      })) {
    fail(ec);
  }
  ClientResponse out;
  out.status = head.get().result_int();
  copy_headers(head.get(), out);
  if (out.status == 200 || out.status == 206) {
    http::response_parser<http::file_body> body{std::move(head)};
    body.body_limit(kNoLimit);
    beast::error_code ec;
    body.get().body().open(file.c_str(), beast::file_mode::write, ec);
    if (ec) {
      impl_->close();
      throw std::runtime_error("cannot write " + file.string() + ": " + ec.message());
    }
    // Per read, so a large file may take longer than the timeout in total.
    while (!body.is_done()) {
      impl_->stream->expires_after(impl_->timeout);
      ec = impl_->run([&](auto handler) {
        http::async_read_some(*impl_->stream, impl_->buffer, body, handler);
      });
      if (ec) fail(ec);
    }
  } else {
    http::response_parser<http::string_body> body{std::move(head)};
    body.body_limit(kNoLimit);
    impl_->stream->expires_after(impl_->timeout);
    if (auto ec = impl_->run([&](auto handler) {
          http::async_read(*impl_->stream, impl_->buffer, body, handler);
        })) {
      fail(ec);
    }
    out.body = body.get().body();
  }
  impl_->close();
  return out;
}

ClientResponse HttpClient::events(const std::string& target,
                                  const std::function<bool(const SseEvent&)>& on_event,
                                  const Headers& headers) {
  Headers all = defaults_;
  all.insert(all.end(), headers.begin(), headers.end());
  all.emplace_back("Accept", "text/event-stream");
  impl_->connect();
  auto req = impl_->make("GET", target, "", all);
  auto fail = [&](beast::error_code ec) {
    impl_->close();
    throw std::runtime_error("GET " + target + ": " + ec.message());
  };
  if (auto ec = impl_->send(req)) fail(ec);
  http::response_parser<http::string_body> parser;
  parser.body_limit(kNoLimit);
  impl_->stream->expires_after(impl_->timeout);
  if (auto ec = impl_->run([&](auto handler) {
        http::async_read_header(*impl_->stream, impl_->buffer, parser, handler);
      })) {
    fail(ec);
  }
  ClientResponse out;
  out.status = parser.get().result_int();
  copy_headers(parser.get(), out);
  if (out.status != 200) {
    impl_->stream->expires_after(impl_->timeout);
    if (auto ec = impl_->run([&](auto handler) {
          http::async_read(*impl_->stream, impl_->buffer, parser, handler);
        })) {
      fail(ec);
    }
    out.body = parser.get().body();
    impl_->close();
    return out;
  }
  std::vector<SseEvent> ready;
  while (!parser.is_done()) {
    impl_->stream->expires_after(impl_->timeout);
    const auto ec = impl_->run([&](auto handler) {
      http::async_read_some(*impl_->stream, impl_->buffer, parser, handler);
    });
    take_events(parser.get().body(), ready);
    for (const SseEvent& e : ready) {
      if (!on_event(e)) {
        impl_->close();
        return out;
      }
    }
    ready.clear();
    if (ec == http::error::end_of_stream || ec == net::error::eof) break;
    if (ec) fail(ec);
  }
  impl_->close();
  return out;
}

std::string raw_exchange(const std::string& host, const std::string& port, const std::string& bytes,
                         std::chrono::milliseconds timeout, bool half_close) {
  net::io_context ioc;
  tcp::resolver resolver(ioc);
  beast::tcp_stream stream(ioc);
  stream.expires_after(timeout);
  beast::error_code ec;
  stream.async_connect(resolver.resolve(host, port), [&](beast::error_code e, auto&&) { ec = e; });
  ioc.run();
  if (ec) throw std::runtime_error("cannot connect to " + host + ":" + port + ": " + ec.message());
  std::string received;
  std::array<char, 4096> buf{};
  std::function<void()> read_more = [&] {
    stream.async_read_some(net::buffer(buf), [&](beast::error_code e, std::size_t n) {
      received.append(buf.data(), n);
      if (!e) read_more();
    });
  };
  stream.expires_after(timeout);
  net::async_write(stream, net::buffer(bytes), [&](beast::error_code e, std::size_t) {
    if (!e && half_close) {
      beast::error_code ignored;
      stream.socket().shutdown(tcp::socket::shutdown_send, ignored);
    }
  });
  read_more();
  ioc.restart();
  ioc.run();
  return received;
}

}  // namespace gearsph::server
