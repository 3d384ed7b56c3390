#include "server/http_types.hpp"

namespace gearsph::server {

namespace {

int hex_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

}  // namespace

std::optional<std::string> percent_decode(std::string_view s, bool plus_is_space) {
  std::string out;
  out.reserve(s.size());
  for (std::size_t i = 0; i < s.size(); ++i) {
    const char c = s[i];
    if (c == '%') {
      if (i + 2 >= s.size()) return std::nullopt;
      const int hi = hex_value(s[i + 1]);
      const int lo = hex_value(s[i + 2]);
      if (hi < 0 || lo < 0) return std::nullopt;
      out.push_back(static_cast<char>(hi * 16 + lo));
      i += 2;
    } else if (c == '+' && plus_is_space) {
      out.push_back(' ');
    } else {
      out.push_back(c);
    }
  }
  return out;
}

std::string percent_encode(std::string_view s) {
  static const char* hex = "0123456789ABCDEF";
  std::string out;
  for (const char c : s) {
    const auto u = static_cast<unsigned char>(c);
    if ((u >= 'a' && u <= 'z') || (u >= 'A' && u <= 'Z') || (u >= '0' && u <= '9') || u == '-' ||
        u == '_' || u == '.' || u == '~' || u == ',') {
      out.push_back(c);
    } else {
      out.push_back('%');
      out.push_back(hex[u >> 4]);
      out.push_back(hex[u & 15]);
    }
  }
  return out;
}

bool parse_target(std::string_view target, Request& out) {
  if (target.empty() || target.front() != '/') return false;
  const auto q = target.find('?');
  const std::string_view path = target.substr(0, q);
  out.path = std::string(path);
  out.segments.clear();
  out.query.clear();
  // "/" has no segments; "/a/b" has two; a trailing "/" adds an empty one.
  if (path.size() > 1) {
    std::size_t start = 1;
    for (;;) {
      const auto slash = path.find('/', start);
      const auto raw = path.substr(start, slash == std::string_view::npos ? slash : slash - start);
      auto decoded = percent_decode(raw, false);
      if (!decoded) return false;
      out.segments.push_back(std::move(*decoded));
      if (slash == std::string_view::npos) break;
      start = slash + 1;
    }
  }
  if (q != std::string_view::npos) {
    std::string_view query = target.substr(q + 1);
    while (!query.empty()) {
      const auto amp = query.find('&');
      const std::string_view pair = query.substr(0, amp);
      if (!pair.empty()) {
        const auto eq = pair.find('=');
        auto name = percent_decode(pair.substr(0, eq), true);
        auto value = eq == std::string_view::npos ? std::optional<std::string>("")
                                                  : percent_decode(pair.substr(eq + 1), true);
        if (!name || !value) return false;
        out.query.emplace_back(std::move(*name), std::move(*value));
      }
      if (amp == std::string_view::npos) break;
      query.remove_prefix(amp + 1);
    }
  }
  return true;
}

std::optional<std::string> Request::query_value(std::string_view name) const {
  for (const auto& [k, v] : query) {
    if (k == name) return v;
  }
  return std::nullopt;
}

std::vector<std::string> Request::query_values(std::string_view name) const {
  std::vector<std::string> out;
  for (const auto& [k, v] : query) {
    if (k == name) out.push_back(v);
  }
  return out;
}

bool wants_html(const Request& req) {
  const std::string accept = req.header(http::field::accept);
  if (req.query_value("f") == std::optional<std::string>("json")) return false;
  if (req.query_value("f") == std::optional<std::string>("html")) return true;
  // A browser asks for text/html first; curl and programs send */* or JSON.
  return accept.find("text/html") != std::string::npos;
}

StringResponse text_response(http::status status, std::string body, std::string content_type) {
  StringResponse res{status, 11};
  res.set(http::field::content_type, content_type);
  res.body() = std::move(body);
  res.prepare_payload();
  return res;
}

StringResponse json_response(http::status status, const nlohmann::json& body) {
  return text_response(status,
                       body.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n",
                       "application/json");
}

unsigned status_code(const Response& r) {
  return std::visit(
      [](const auto& m) -> unsigned {
        if constexpr (std::is_same_v<std::decay_t<decltype(m)>, EventStream>) {
          return m.head.result_int();
        } else {
          return m.result_int();
        }
      },
      r);
}

}  // namespace gearsph::server
