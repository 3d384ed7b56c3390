#pragma once
// One HTTP/1.1 connection: reads a request within explicit limits and
// timeouts, has the router map it to a response (on the handler pool when
// the route may block), writes the response, and repeats while the client
// keeps the connection alive. An event-stream response turns the
// connection into a Server-Sent Events stream fed by the event hub.
#include <array>
#include <memory>
#include <optional>
#include <string>

#include <boost/asio/steady_timer.hpp>
#include <boost/asio/thread_pool.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>

#include "server/event_hub.hpp"
#include "server/router.hpp"

namespace gearsph::server {

// The threads handlers run on, by lane (the I/O lane is the session's own).
struct HandlerPools {
  boost::asio::thread_pool& store;
  boost::asio::thread_pool& slow;
};

class HttpSession : public std::enable_shared_from_this<HttpSession> {
 public:
  HttpSession(boost::asio::ip::tcp::socket&& socket, const Router& router, HandlerPools pools);
  ~HttpSession();
  HttpSession(const HttpSession&) = delete;
  HttpSession& operator=(const HttpSession&) = delete;

  void run();

 private:
  // Request / response cycle.
  void wait_for_request();
  void read_header();
  void on_header(boost::beast::error_code ec);
  void read_body();
  void on_body(boost::beast::error_code ec);
  void dispatch();
  void send(std::shared_ptr<Request> req, Response res);
  void refuse(Response res);  // answer, then close without reading the rest
  template <class Body>
  void write(std::shared_ptr<http::response<Body>> msg, bool close);
  template <class Body>
  void write_some(std::shared_ptr<http::response<Body>> msg,
                  std::shared_ptr<http::response_serializer<Body>> sr, bool close);
  void after_write(bool close);

  // Closing: stop sending, take (and drop) what the client still sends for
  // a moment so it can read the answer instead of a reset, then close.
  void linger();
  void drain();
  void close();

  // Server-Sent Events.
  void start_events(EventStream es);
  void pump();
  void write_events(std::string text, bool last);
  void arm_keepalive();
  void watch_for_close();
  void resnapshot();

  boost::beast::tcp_stream stream_;
  boost::beast::flat_buffer buffer_;
  std::optional<http::request_parser<http::string_body>> parser_;
  const Router& router_;
  Services& services_;
  HandlerPools pools_;
  bool first_request_ = true;
  bool closed_ = false;
  std::array<char, 4096> sink_{};
  std::size_t drained_ = 0;

  std::unique_ptr<EventHub::Subscription> subscription_;
  std::string job_filter_;  // "" for the stream of all jobs
  std::uint64_t last_id_ = 0;
  std::string pending_;  // text to send before the next events
  std::string chunk_;    // the chunk being written
  bool writing_ = false;
  bool streaming_ = false;       // counted in Services::event_streams
  bool chunked_ = true;          // false for an HTTP/1.0 client: the events end with the connection
  bool final_snapshot_ = false;  // the status sent first was already final
  bool refreshing_ = false;      // a status snapshot is being read from the store
  boost::asio::steady_timer keepalive_;
};

}  // namespace gearsph::server
