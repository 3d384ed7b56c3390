#include "server/listener.hpp"

#include <cstdio>

#include <boost/asio/dispatch.hpp>
#include <boost/asio/strand.hpp>

#include "server/http_session.hpp"
#include "server/log.hpp"

namespace gearsph::server {

namespace net = boost::asio;
using tcp = net::ip::tcp;

Listener::Listener(net::io_context& ioc, const tcp::endpoint& endpoint, const Router& router,
                   HandlerPools pools)
    : ioc_(ioc),
      acceptor_(net::make_strand(ioc)),
      retry_(acceptor_.get_executor()),
      router_(router),
      pools_(pools) {
  acceptor_.open(endpoint.protocol());
  acceptor_.set_option(net::socket_base::reuse_address(true));
  acceptor_.bind(endpoint);
  acceptor_.listen(net::socket_base::max_listen_connections);
}

unsigned short Listener::port() const {
  return acceptor_.local_endpoint().port();
}

void Listener::run() {
  net::dispatch(acceptor_.get_executor(), [self = shared_from_this()] { self->accept(); });
}

void Listener::stop() {
  net::dispatch(acceptor_.get_executor(), [self = shared_from_this()] {
    boost::system::error_code ec;
    self->retry_.cancel();
    self->acceptor_.close(ec);
  });
}

void Listener::accept() {
  // Each connection gets a strand: its handlers never run concurrently.
  acceptor_.async_accept(
      net::make_strand(ioc_),
      [self = shared_from_this()](boost::system::error_code ec, tcp::socket socket) {
        if (ec == net::error::operation_aborted || !self->acceptor_.is_open()) return;
        if (ec) {
          // Out of file descriptors, say: wait a moment rather than spin.
          log_line(LogLevel::warning, "gearsph serve: accept: %s\n", ec.message().c_str());
          self->retry_.expires_after(std::chrono::milliseconds(100));
          self->retry_.async_wait([self](boost::system::error_code wec) {
            if (!wec) self->accept();
          });
          return;
        }
        std::make_shared<HttpSession>(std::move(socket), self->router_, self->pools_)->run();
        self->accept();
      });
}

}  // namespace gearsph::server
