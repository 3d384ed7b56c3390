#pragma once
// SHA-256 (FIPS 180-4, OpenSSL's libcrypto), for what the job store keeps of a secret: the hash
// of a session id, never the id itself, so that a copy of the store opens
// no session.
#include <string>
#include <string_view>

namespace gearsph::server {

// The digest of `data` as 64 lowercase hex digits.
std::string sha256_hex(std::string_view data);

}  // namespace gearsph::server
