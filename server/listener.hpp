#pragma once
// Accepts connections and hands each to its own HttpSession (on its own strand).
#include <memory>

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/steady_timer.hpp>
#include <boost/asio/thread_pool.hpp>

#include "server/http_session.hpp"
#include "server/router.hpp"

namespace gearsph::server {

class Listener : public std::enable_shared_from_this<Listener> {
 public:
  // Binds and listens at once (throws if the address is taken).
  Listener(boost::asio::io_context& ioc, const boost::asio::ip::tcp::endpoint& endpoint,
           const Router& router, HandlerPools pools);
  unsigned short port() const;
  void run();
  void stop();  // no more connections; thread-safe

 private:
  void accept();

  boost::asio::io_context& ioc_;
  boost::asio::ip::tcp::acceptor acceptor_;
  boost::asio::steady_timer retry_;
  const Router& router_;
  HandlerPools pools_;
};

}  // namespace gearsph::server
