#include "server/http_session.hpp"

#include <sys/socket.h>

#include <cerrno>

#include <boost/asio/dispatch.hpp>
#include <boost/asio/post.hpp>
#include <boost/asio/write.hpp>

#include "server/client_identity.hpp"
#include "server/problem.hpp"

namespace gearsph::server {

namespace beast = boost::beast;
namespace net = boost::asio;
using tcp = net::ip::tcp;

namespace {

// How long a closing connection still takes bytes the client sends.
constexpr std::chrono::seconds kLinger{2};
constexpr std::size_t kLingerBytes = 16 << 20;

// Whether the request line in `buffer` ends with "HTTP/" DIGIT "." DIGIT
// (RFC 9112 section 2.3).
bool well_formed_version(const beast::flat_buffer& buffer) {
  const auto data = buffer.data();
  std::string_view text(static_cast<const char*>(data.data()), data.size());
  text = text.substr(0, text.find("\r\n"));
  const auto space = text.rfind(' ');
  if (space == std::string_view::npos) return false;
  const std::string_view v = text.substr(space + 1);
  const auto digit = [](char c) { return c >= '0' && c <= '9'; };
  return v.size() == 8 && v.substr(0, 5) == "HTTP/" && digit(v[5]) && v[6] == '.' && digit(v[7]);
}

}  // namespace

HttpSession::HttpSession(tcp::socket&& socket, const Router& router, HandlerPools pools)
    : stream_(std::move(socket)),
      router_(router),
      services_(router.services()),
      pools_(pools),
      keepalive_(stream_.get_executor()) {
  ++services_.connections;
}

HttpSession::~HttpSession() {
  --services_.connections;
  if (streaming_) --services_.event_streams;
}

void HttpSession::run() {
  net::dispatch(stream_.get_executor(), [self = shared_from_this()] {
    if (self->services_.connections > self->services_.config.limits.max_connections) {
      StringResponse res = problem::plain(http::status::service_unavailable,
                                          "too many open connections; try again shortly", "");
      res.set(http::field::retry_after, "1");
      self->refuse(std::move(res));
      return;
    }
    self->wait_for_request();
  });
}

void HttpSession::wait_for_request() {
  parser_.emplace();
  parser_->header_limit(services_.config.limits.max_header_bytes);
  parser_->body_limit(services_.config.limits.max_body_bytes);
  if (buffer_.size() > 0) {  // the client already sent (part of) the next request
    read_header();
    return;
  }
  // Idle until the request's first byte; the header timeout starts then.
  const auto& t = services_.config.timeouts;
  stream_.expires_after(first_request_ ? t.header : t.idle);
  stream_.async_read_some(buffer_.prepare(4096),
                          [self = shared_from_this()](beast::error_code ec, std::size_t n) {
                            if (ec) return self->close();
                            self->buffer_.commit(n);
                            self->read_header();
                          });
}

void HttpSession::read_header() {
  first_request_ = false;
  stream_.expires_after(services_.config.timeouts.header);
  http::async_read_header(
      stream_, buffer_, *parser_,
      [self = shared_from_this()](beast::error_code ec, std::size_t) { self->on_header(ec); });
}

void HttpSession::on_header(beast::error_code ec) {
  if (ec == http::error::end_of_stream || ec == beast::error::timeout ||
      ec == net::error::operation_aborted || ec == net::error::connection_reset ||
      ec == net::error::eof) {
    return close();
  }
  if (ec == http::error::body_limit) {  // a declared Content-Length over the limit
    return refuse(problem::plain(
        http::status::payload_too_large,
        "the body exceeds " + std::to_string(services_.config.limits.max_body_bytes) + " bytes",
        ""));
  }
  if (ec == http::error::header_limit) {
    return refuse(problem::plain(http::status::request_header_fields_too_large,
                                 "the request line and headers exceed " +
                                     std::to_string(services_.config.limits.max_header_bytes) +
                                     " bytes",
                                 ""));
  }
  if (ec == http::error::bad_version) {
    // Beast takes only 1.x: a well-formed other version (HTTP/2.0) gets
    // 505; anything else is a malformed request line (RFC 9112 section
    // 2.3), 400.
    if (well_formed_version(buffer_)) {
      return refuse(problem::plain(http::status::http_version_not_supported,
                                   "this server speaks HTTP/1.1 (and HTTP/1.0)", ""));
    }
    return refuse(problem::plain(http::status::bad_request,
                                 "the request line does not end with an HTTP version such as "
                                 "HTTP/1.1",
                                 ""));
  }
  if (ec) {
    return refuse(problem::plain(http::status::bad_request,
                                 "the request is not valid HTTP/1.1: " + ec.message(), ""));
  }
  if (auto refusal = router_.screen(parser_->get().base())) return refuse(std::move(*refusal));
  const std::string_view expect = parser_->get()[http::field::expect];
  if (beast::iequals(expect, "100-continue") && !parser_->is_done()) {
    // The client waits for this before it sends the body.
    auto cont = std::make_shared<http::response<http::empty_body>>(http::status::continue_, 11);
    stream_.expires_after(services_.config.timeouts.write);
    http::async_write(stream_, *cont,
                      [self = shared_from_this(), cont](beast::error_code wec, std::size_t) {
                        if (wec) return self->close();
                        self->read_body();
                      });
    return;
  }
  read_body();
}

void HttpSession::read_body() {
  stream_.expires_after(services_.config.timeouts.body);
  http::async_read(
      stream_, buffer_, *parser_,
      [self = shared_from_this()](beast::error_code ec, std::size_t) { self->on_body(ec); });
}

void HttpSession::on_body(beast::error_code ec) {
  if (ec == http::error::body_limit) {
    return refuse(problem::plain(
        http::status::payload_too_large,
        "the body exceeds " + std::to_string(services_.config.limits.max_body_bytes) + " bytes",
        ""));
  }
  if (ec == beast::error::timeout) {
    // The socket is closed already; nothing can be answered.
    return close();
  }
  if (ec == http::error::end_of_stream || ec == net::error::eof ||
      ec == net::error::connection_reset || ec == net::error::operation_aborted) {
    return close();
  }
  if (ec) {
    return refuse(problem::plain(http::status::bad_request,
                                 "the request body is not valid HTTP/1.1: " + ec.message(), ""));
  }
  dispatch();
}

void HttpSession::dispatch() {
  auto req = std::make_shared<Request>();
  req->msg = parser_->release();
  {
    beast::error_code ec;
    const auto peer = stream_.socket().remote_endpoint(ec);
    if (!ec) {
      // Every X-Forwarded-For line, in order (RFC 9110, 5.3: one list).
      std::string forwarded;
      const auto lines = req->msg.equal_range("X-Forwarded-For");
      for (auto it = lines.first; it != lines.second; ++it) {
        if (!forwarded.empty()) forwarded += ',';
        forwarded += std::string(it->value());
      }
      req->client =
          forwarded_client(peer.address().to_string(), forwarded, services_.config.trusted_proxies);
    }
  }
  Router::Match match = router_.match(*req);
  const Lane lane = match.lane();
  if (lane == Lane::io) {
    send(req, router_.respond(*req, std::move(match)));
    return;
  }
  // Handlers that may block run on their pool; the answer comes back to
  // this connection's strand. Meanwhile nothing reads the socket: a peek
  // tells whether the client closed it (0 bytes: an orderly close; an
  // error: a reset), so that long work for nobody stops.
  req->gone = [fd = stream_.socket().native_handle()] {
    char c = 0;
    const ssize_t n = ::recv(fd, &c, 1, MSG_PEEK | MSG_DONTWAIT);
    return n == 0 || (n < 0 && errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR);
  };
  net::thread_pool& pool = lane == Lane::store ? pools_.store : pools_.slow;
  net::post(pool, [self = shared_from_this(), ex = stream_.get_executor(), req,
                   m = std::move(match)]() mutable {
    Response res = self->router_.respond(*req, std::move(m));
    net::post(ex, [self, req, r = std::move(res)]() mutable { self->send(req, std::move(r)); });
  });
}

void HttpSession::send(std::shared_ptr<Request> req, Response res) {
  // An HTTP/1.0 client gets one answer per connection.
  const bool keep_alive = req->msg.version() >= 11 && req->msg.keep_alive() && !services_.stopping;
  std::visit(
      [&](auto& m) {
        using M = std::decay_t<decltype(m)>;
        if constexpr (std::is_same_v<M, EventStream>) {
          if (++services_.event_streams > services_.max_event_streams()) {
            --services_.event_streams;
            StringResponse busy = problem::plain(
                http::status::service_unavailable,
                "too many open event streams (" + std::to_string(services_.max_event_streams()) +
                    ", half of --max-connections); try again shortly, or poll /jobs/{id}",
                req->path);
            busy.set(http::field::retry_after, "5");
            busy.keep_alive(false);
            write(std::make_shared<StringResponse>(std::move(busy)), true);
            return;
          }
          streaming_ = true;
          chunked_ = req->msg.version() >= 11;
          start_events(std::move(m));
        } else {
          m.keep_alive(keep_alive);
          const bool close = !keep_alive || m.need_eof();
          write(std::make_shared<M>(std::move(m)), close);
        }
      },
      res);
}

void HttpSession::refuse(Response res) {
  std::visit(
      [&](auto& m) {
        using M = std::decay_t<decltype(m)>;
        if constexpr (!std::is_same_v<M, EventStream>) {
          m.keep_alive(false);
          write(std::make_shared<M>(std::move(m)), true);
        }
      },
      res);
}

template <class Body>
void HttpSession::write(std::shared_ptr<http::response<Body>> msg, bool close) {
  auto sr = std::make_shared<http::response_serializer<Body>>(*msg);
  write_some(std::move(msg), std::move(sr), close);
}

// Piece by piece, so the write timeout is about a client that stops taking
// bytes, not about how long a large file takes.
template <class Body>
void HttpSession::write_some(std::shared_ptr<http::response<Body>> msg,
                             std::shared_ptr<http::response_serializer<Body>> sr, bool close) {
  stream_.expires_after(services_.config.timeouts.write);
  auto& serializer = *sr;
  http::async_write_some(stream_, serializer,
                         [self = shared_from_this(), msg = std::move(msg), sr = std::move(sr),
                          close](beast::error_code ec, std::size_t) mutable {
                           if (ec) return self->close();
                           if (!sr->is_done())
                             return self->write_some(std::move(msg), std::move(sr), close);
                           self->after_write(close);
                         });
}

void HttpSession::after_write(bool close) {
  if (close) return linger();
  wait_for_request();
}

void HttpSession::linger() {
  beast::error_code ec;
  stream_.socket().shutdown(tcp::socket::shutdown_send, ec);
  if (ec) return close();
  stream_.expires_after(kLinger);  // one deadline for the whole drain
  drain();
}

void HttpSession::drain() {
  stream_.async_read_some(net::buffer(sink_),
                          [self = shared_from_this()](beast::error_code ec, std::size_t n) {
                            self->drained_ += n;
                            if (ec || self->drained_ > kLingerBytes) return self->close();
                            self->drain();
                          });
}

void HttpSession::close() {
  if (closed_) return;
  closed_ = true;
  keepalive_.cancel();
  subscription_.reset();
  beast::error_code ec;
  stream_.socket().shutdown(tcp::socket::shutdown_both, ec);
  stream_.close();
}

// ---- Server-Sent Events ----------------------------------------------------

void HttpSession::start_events(EventStream es) {
  job_filter_ = es.job_id;
  EventHub& hub = services_.hub;
  subscription_ =
      hub.subscribe(job_filter_, [weak = weak_from_this(), ex = stream_.get_executor()] {
        net::post(ex, [weak] {
          if (auto self = weak.lock()) self->pump();
        });
      });
  // The handler chose where to start (events published since are still in
  // the hub's ring: the first pump finds them).
  last_id_ = es.after;
  pending_ = "retry: 3000\n\n" + es.first;
  final_snapshot_ = es.final;

  auto head = std::make_shared<http::response<http::empty_body>>(std::move(es.head));
  head->keep_alive(false);
  // HTTP/1.0 has no chunks: the stream is the body, ended by closing.
  head->chunked(chunked_);
  auto sr = std::make_shared<http::response_serializer<http::empty_body>>(*head);
  stream_.expires_after(services_.config.timeouts.write);
  // The hub may post pump() while the header is on its way: it must wait,
  // as two writes on one stream at once are undefined (Beast asserts).
  writing_ = true;
  http::async_write_header(
      stream_, *sr, [self = shared_from_this(), head, sr](beast::error_code ec, std::size_t) {
        self->writing_ = false;
        if (ec) return self->close();
        self->watch_for_close();
        self->arm_keepalive();
        self->pump();
      });
}

void HttpSession::resnapshot() {
  // The job's status is read from the store, off the I/O threads; the
  // stream goes on from the hub's position before the read.
  refreshing_ = true;
  net::post(pools_.store, [self = shared_from_this(), ex = stream_.get_executor()] {
    Services& s = self->services_;
    const std::uint64_t now = s.hub.last_id();
    std::string text;
    bool final = false;
    try {
      if (const auto job = s.store.job(self->job_filter_)) {
        Event e;
        e.id = now;
        e.type = "status";
        e.data = s.status_of(*job).dump();
        text = sse_text(e);
        final = is_terminal_status(job->status);
      }
    } catch (const std::exception&) {
      // The store is away: the stream goes on without the snapshot.
    }
    net::post(ex, [self, now, text = std::move(text), final] {
      self->refreshing_ = false;
      self->pending_ += text;
      self->last_id_ = now;
      self->final_snapshot_ = self->final_snapshot_ || final;
      self->pump();
    });
  });
}

void HttpSession::pump() {
  if (closed_ || writing_ || refreshing_) return;
  EventHub& hub = services_.hub;
  std::string text = std::move(pending_);
  pending_.clear();
  bool last = false;
  if (final_snapshot_) {
    // The job had finished already: its final status is all there is to send.
    write_events(std::move(text), true);
    return;
  }
  const EventHub::Batch batch = hub.after(last_id_, job_filter_, 256);
  if (batch.gap) {
    // Events were dropped before this stream got them. Nothing older than
    // what replaces them may follow: a job's stream gets its status anew,
    // the stream of all jobs a reset (the client fetches /jobs again).
    pending_ = std::move(text);
    if (!job_filter_.empty()) return resnapshot();
    const std::uint64_t now = hub.last_id();
    pending_ += "id: " + std::to_string(now) + "\nevent: reset\ndata: {}\n\n";
    last_id_ = now;
    return pump();
  }
  last_id_ = batch.seen;
  for (const Event& e : batch.events) {
    text += sse_text(e);
    if (e.terminal && !job_filter_.empty()) {
      last = true;  // a job's stream ends with its final status
      break;
    }
  }
  if (hub.closed() && batch.events.empty()) last = true;
  if (text.empty() && !last) return;
  write_events(std::move(text), last);
}

void HttpSession::write_events(std::string text, bool last) {
  writing_ = true;
  chunk_.clear();
  if (!chunked_) {
    chunk_ = std::move(text);
  } else {
    if (!text.empty()) {
      char size[20];
      std::snprintf(size, sizeof size, "%zx\r\n", text.size());
      chunk_ = size + text + "\r\n";
    }
    if (last) chunk_ += "0\r\n\r\n";
  }
  stream_.expires_after(services_.config.timeouts.write);
  net::async_write(stream_, net::buffer(chunk_),
                   [self = shared_from_this(), last](beast::error_code ec, std::size_t) {
                     self->writing_ = false;
                     // Done: close (the watch_for_close read is still pending, so no linger).
                     if (ec || last) return self->close();
                     self->pump();
                   });
}

void HttpSession::arm_keepalive() {
  keepalive_.expires_after(services_.config.timeouts.sse_keepalive);
  keepalive_.async_wait([weak = weak_from_this()](beast::error_code ec) {
    auto self = weak.lock();
    if (!self || ec || self->closed_) return;
    if (!self->writing_) {
      self->pending_ += ": keep-alive\n\n";
      self->pump();
    }
    self->arm_keepalive();
  });
}

void HttpSession::watch_for_close() {
  // The client sends nothing on an event stream; a read that ends means it left.
  stream_.socket().async_read_some(net::buffer(sink_),
                                   [self = shared_from_this()](beast::error_code ec, std::size_t) {
                                     if (ec) return self->close();
                                     self->watch_for_close();
                                   });
}

}  // namespace gearsph::server
