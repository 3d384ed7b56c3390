// /login: the dashboard behind --token-file. GET says whether a token is
// needed and whether the request carries it; POST checks it and sets the
// cookie; DELETE clears it. A
// browser cannot put the token on everything it fetches (images, downloads
// and EventSource take no headers), so the login call checks the token once
// and sets a cookie holding it: HttpOnly (scripts cannot read it) and
// SameSite=Strict (other sites' pages do not send it).
#include "server/problem.hpp"
#include "server/router.hpp"
#include "server/routes.hpp"
#include "server/submission.hpp"

namespace gearsph::server::routes {

namespace {

// Thirty days: a dashboard asks for the token once, not every morning.
constexpr int kCookieMaxAge_s = 30 * 24 * 3600;

// Cookie values allow no spaces, quotes, commas, semicolons or backslashes.
std::string cookie_value(std::string_view token) {
  static const char* hex = "0123456789ABCDEF";
  std::string out;
  for (const char c : token) {
    const auto u = static_cast<unsigned char>(c);
    if (std::isalnum(u) || c == '-' || c == '.' || c == '_' || c == '~') {
      out.push_back(c);
    } else {
      out.push_back('%');
      out.push_back(hex[u >> 4]);
      out.push_back(hex[u & 15]);
    }
  }
  return out;
}

std::string cookie(const Request& req, const std::string& value, int max_age_s) {
  std::string c = std::string(kSessionCookie) + "=" + value +
                  "; Path=/; HttpOnly; SameSite=Strict; Max-Age=" + std::to_string(max_age_s);
  // Behind a TLS-terminating proxy the browser only sends it over TLS.
  if (req.msg["X-Forwarded-Proto"] == "https") {
    c += "; Secure";
  }
  return c;
}

}  // namespace

Response login_state(Services& s, Request& req) {
  const bool required = !s.config.token.empty();
  return json_response(http::status::ok,
                       {{"token_required", required},
                        {"signed_in", !required || carries_token(req.msg.base(), s.config.token)}});
}

Response login(Services& s, Request& req) {
  if (s.config.token.empty()) {
    // Nothing to log in to: every request is answered without a token.
    return StringResponse{http::status::no_content, 11};
  }
  std::string presented;
  const std::string_view auth = req.msg[http::field::authorization];
  if (auth.size() > 7 && (auth.substr(0, 7) == "Bearer " || auth.substr(0, 7) == "bearer ")) {
    presented = std::string(auth.substr(7));
  } else {
    auto body = read_json_body(req);
    if (auto* error = std::get_if<StringResponse>(&body)) return std::move(*error);
    const nlohmann::json& j = std::get<nlohmann::json>(body);
    if (!j.is_object() || !j.contains("token") || !j["token"].is_string()) {
      problem::Problem p;
      p.status = http::status::bad_request;
      p.type = problem::kInvalidParameter;
      p.title = "No token";
      p.detail = "send {\"token\": \"...\"} (or \"Authorization: Bearer <token>\")";
      p.instance = req.path;
      p.extra["errors"] = {{{"pointer", "/token"}, {"detail", "is required: the access token"}}};
      return problem::make(p);
    }
    presented = j["token"].get<std::string>();
  }
  if (!token_matches(presented, s.config.token)) {
    StringResponse res =
        problem::plain(http::status::unauthorized, "this is not the server's token", req.path);
    res.set(http::field::www_authenticate, "Bearer realm=\"gearsph\"");
    return res;
  }
  StringResponse res{http::status::no_content, 11};
  res.set(http::field::set_cookie, cookie(req, cookie_value(presented), kCookieMaxAge_s));
  return res;
}

Response logout(Services&, Request& req) {
  StringResponse res{http::status::no_content, 11};
  res.set(http::field::set_cookie, cookie(req, "", 0));
  return res;
}

}  // namespace gearsph::server::routes
