#include "server/client_identity.hpp"

#include <algorithm>
#include <optional>

#include <boost/asio/ip/address.hpp>

namespace gearsph::server {

namespace {

// The address in its canonical text ("::1", not "0:0::1"); nothing if not one.
std::optional<std::string> canonical(std::string_view text) {
  while (!text.empty() && (text.front() == ' ' || text.front() == '\t')) text.remove_prefix(1);
  while (!text.empty() && (text.back() == ' ' || text.back() == '\t')) text.remove_suffix(1);
  boost::system::error_code ec;
  const auto a = boost::asio::ip::make_address(std::string(text), ec);
  if (ec) return std::nullopt;
  // An IPv4 client seen through a dual-stack socket is the same client.
  if (a.is_v6() && a.to_v6().is_v4_mapped()) {
    return boost::asio::ip::make_address_v4(boost::asio::ip::v4_mapped, a.to_v6()).to_string();
  }
  return a.to_string();
}

bool is_trusted(const std::string& address, const std::vector<std::string>& trusted) {
  return std::any_of(trusted.begin(), trusted.end(), [&](const std::string& t) {
    const auto c = canonical(t);
    return c && *c == address;
  });
}

}  // namespace

bool is_ip_address(std::string_view text) {
  return canonical(text).has_value();
}

std::string forwarded_client(const std::string& peer, std::string_view forwarded,
                             const std::vector<std::string>& trusted) {
  const auto from = canonical(peer);
  if (!from) return peer;
  std::string client = *from;
  if (trusted.empty() || !is_trusted(client, trusted)) return client;
  while (!forwarded.empty()) {
    const auto comma = forwarded.rfind(',');
    const std::string_view entry =
        comma == std::string_view::npos ? forwarded : forwarded.substr(comma + 1);
    forwarded = comma == std::string_view::npos ? std::string_view() : forwarded.substr(0, comma);
    const auto hop = canonical(entry);
    if (!hop) break;
    client = *hop;
    if (!is_trusted(client, trusted)) break;
  }
  return client;
}

}  // namespace gearsph::server
