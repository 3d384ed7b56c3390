#pragma once
// Who a request comes from, for failed logins and the queue quota
// (docs/api.md, Queue quotas): the address of the connection's peer, or,
// when that peer is a proxy given with --trusted-proxy, the address its
// X-Forwarded-For names; and for the quota, the authenticated identity
// where the request has one.
#include <string>
#include <string_view>
#include <vector>

namespace gearsph::server {

// The client's address. `forwarded` is the request's X-Forwarded-For (its
// lines joined with ","), heeded only when `peer` is one of `trusted`: read
// from the right, the first address that is not a trusted proxy is the
// client (each proxy appends the address it got the request from, so
// entries left of an untrusted one are the client's to invent). An entry
// that is not an IP address stops the walk at the hop before it.
std::string forwarded_client(const std::string& peer, std::string_view forwarded,
                             const std::vector<std::string>& trusted);

// Whether `text` is an IPv4 or IPv6 address (what --trusted-proxy takes).
bool is_ip_address(std::string_view text);

}  // namespace gearsph::server
