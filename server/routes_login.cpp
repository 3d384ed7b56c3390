// /login: the dashboard behind --token-file. GET says whether a token is
// needed and whether the request carries it; POST checks it and opens a
// session; DELETE revokes the session and clears its cookie. A browser
// cannot put the token on everything it fetches (images, downloads and
// EventSource take no headers), so the login call checks the token once
// and sets a cookie holding an opaque session id (sessions.hpp), never the
// token: HttpOnly (scripts cannot read it) and SameSite=Strict (other
// sites' pages do not send it). Failed logins are limited per client
// address (LoginThrottle: 429 with Retry-After).
#include "server/problem.hpp"
#include "server/router.hpp"
#include "server/routes.hpp"
#include "server/submission.hpp"

namespace gearsph::server::routes {

namespace {

std::string cookie(const Request& req, const std::string& value, long long max_age_s) {
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
  return json_response(
      http::status::ok,
      {{"token_required", required},
       {"signed_in", !required || carries_credential(req.msg.base(), s.config.token, s.sessions)}});
}

Response login(Services& s, Request& req) {
  if (s.config.token.empty()) {
    // Nothing to log in to: every request is answered without a token.
    return StringResponse{http::status::no_content, 11};
  }
  // RFC 6585, 4: too many failed tries from this address; the right token
  // waits too, or guessing would go on at network speed.
  if (const auto wait = s.login_throttle.wait(req.client); wait.count() > 0) {
    problem::Problem p;
    p.status = http::status::too_many_requests;
    p.type = "about:blank";
    p.title = "Too Many Requests";
    p.detail = std::to_string(kLoginFailuresPerMinute) +
               " failed logins from this address within a minute; try again in " +
               std::to_string(wait.count()) + " s";
    p.instance = req.path;
    StringResponse res = problem::make(p);
    res.set(http::field::retry_after, std::to_string(wait.count()));
    return res;
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
    s.login_throttle.failed(req.client);
    StringResponse res =
        problem::plain(http::status::unauthorized, "this is not the server's token", req.path);
    res.set(http::field::www_authenticate, "Bearer realm=\"gearsph\"");
    return res;
  }
  s.login_throttle.succeeded(req.client);
  StringResponse res{http::status::no_content, 11};
  res.set(http::field::set_cookie, cookie(req, s.sessions.open(), s.sessions.lifetime().count()));
  return res;
}

Response logout(Services& s, Request& req) {
  // The session ends here, not only in this browser: a copied cookie is
  // refused from now on.
  if (auto id = session_cookie(req.msg.base())) s.sessions.close(*id);
  StringResponse res{http::status::no_content, 11};
  res.set(http::field::set_cookie, cookie(req, "", 0));
  return res;
}

}  // namespace gearsph::server::routes
