#include "solver/core/schema_wording.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <optional>

namespace gearsph::jsonschema::wording {
namespace {

std::string dump(const json& value) {
  // `replace` because instances built in code may hold invalid UTF-8.
  return value.dump(-1, ' ', false, json::error_handler_t::replace);
}

bool is_continuation_byte(char c) {
  return (static_cast<unsigned char>(c) & 0xC0) == 0x80;
}

// The first `n` code points of `s`.
std::string utf8_prefix(const std::string& s, std::size_t n) {
  std::size_t seen = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (!is_continuation_byte(s[i]) && seen++ == n) return s.substr(0, i);
  }
  return s;
}

std::string join(const std::vector<std::string>& parts, const std::string& separator) {
  std::string out;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    if (i > 0) out += separator;
    out += parts[i];
  }
  return out;
}

// Fixed notation is kept for 1e-4 <= |v| < 1e-3, where the shortest form
// would be the less readable "1e-04".
std::string format_double(double v) {
  char buf[64];
  const double magnitude = std::fabs(v);
  const bool prefer_fixed = magnitude >= 1e-4 && magnitude < 1e-3;
  const auto result = prefer_fixed
                          ? std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed)
                          : std::to_chars(buf, buf + sizeof buf, v);
  return result.ec == std::errc() ? std::string(buf, result.ptr) : "a number";
}

// Appends `v` in compact JSON to `out` unless that would exceed `budget`
// characters. Work is bounded by the budget and a small depth, whatever the
// size of `v` (json::dump would walk all of it).
bool render_within(const json& v, std::string& out, std::size_t budget, int depth = 0) {
  constexpr int kMaxRenderDepth = 8;
  if (depth > kMaxRenderDepth) return false;
  if (v.is_structured()) {
    const bool object = v.is_object();
    out += object ? '{' : '[';
    for (auto it = v.begin(); it != v.end(); ++it) {
      if (it != v.begin()) out += ',';
      if (object && it.key().size() > budget) return false;
      if (object) out += quote(it.key()) + ':';
      if (out.size() > budget || !render_within(it.value(), out, budget, depth + 1)) return false;
    }
    out += object ? '}' : ']';
  } else if (v.is_string() && v.get_ref<const std::string&>().size() > budget) {
    return false;
  } else {
    out += dump(v);
  }
  return out.size() <= budget;
}

std::optional<std::string> short_json(const json& v) {
  std::string text;
  if (!render_within(v, text, kShortValue)) return std::nullopt;
  return text;
}

std::string lower_ascii(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// Optimal string alignment distance: Levenshtein plus adjacent swaps, the
// typical typo ("palte" -> "plate").
std::size_t edit_distance(const std::string& a, const std::string& b) {
  const std::size_t n = a.size(), m = b.size();
  std::vector<std::vector<std::size_t>> d(n + 1, std::vector<std::size_t>(m + 1, 0));
  for (std::size_t i = 0; i <= n; ++i) d[i][0] = i;
  for (std::size_t j = 0; j <= m; ++j) d[0][j] = j;
  for (std::size_t i = 1; i <= n; ++i) {
    for (std::size_t j = 1; j <= m; ++j) {
      const std::size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) {
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
      }
    }
  }
  return d[n][m];
}

}  // namespace

std::size_t count_code_points(const std::string& s) {
  return static_cast<std::size_t>(
      std::count_if(s.begin(), s.end(), [](char c) { return !is_continuation_byte(c); }));
}

std::string plural(std::size_t n, const std::string& noun) {
  return std::to_string(n) + " " + noun + (n == 1 ? "" : "s");
}

std::string quote(const std::string& s) {
  return dump(json(s));
}

std::string join_words(const std::vector<std::string>& parts, const std::string& conjunction) {
  if (parts.size() <= 1) return join(parts, "");
  std::vector<std::string> head(parts.begin(), parts.end() - 1);
  return join(head, ", ") + " " + conjunction + " " + parts.back();
}

std::string join_or(const std::vector<std::string>& parts) {
  return join_words(parts, "or");
}

std::string join_listed(const std::vector<std::string>& parts) {
  if (parts.size() <= kMaxListed) return join(parts, ", ");
  std::vector<std::string> head(parts.begin(), parts.begin() + kMaxListed);
  return join(head, ", ") + " and " + std::to_string(parts.size() - kMaxListed) + " more";
}

std::string format_number(const json& v) {
  if (v.is_number_unsigned()) return std::to_string(v.get<std::uint64_t>());
  if (v.is_number_integer()) return std::to_string(v.get<std::int64_t>());
  return format_double(v.get<double>());
}

std::string kind_of(const json& v) {
  switch (v.type()) {
    case json::value_t::null:
      return "null";
    case json::value_t::boolean:
      return "a boolean";
    case json::value_t::string:
      return "a string";
    case json::value_t::array:
      return "an array";
    case json::value_t::object:
      return "an object";
    case json::value_t::number_integer:
    case json::value_t::number_unsigned:
    case json::value_t::number_float:
      return "a number";
    default:
      return "a value";
  }
}

std::string describe_value(const json& v) {
  if (v.is_number()) return format_number(v);
  if (v.is_string()) {
    const auto& s = v.get_ref<const std::string&>();
    if (count_code_points(s) <= kShortValue) return quote(s);
    const std::string quoted = quote(utf8_prefix(s, kShortValue - 10));
    return quoted.substr(0, quoted.size() - 1) + "...\"";
  }
  if (auto text = short_json(v)) return *text;
  if (v.is_array()) return "an array of " + plural(v.size(), "item");
  if (v.is_object()) return "an object with " + plural(v.size(), "field");
  return kind_of(v);
}

std::string expected_value(const json& v) {
  if (!v.is_structured() || short_json(v)) return describe_value(v);
  return "the required fixed " + std::string(v.is_array() ? "array" : "object");
}

std::string value_suffix(const json& v) {
  if (v.is_string() || v.is_number() || v.is_boolean()) return " (" + describe_value(v) + ")";
  return "";
}

std::string did_you_mean(const std::string& got, const std::vector<std::string>& candidates) {
  constexpr std::size_t kMaxDistance = 2;
  constexpr std::size_t kMaxCompared = 256;  // the distance is quadratic in length
  if (got.size() > kMaxCompared) return "";
  const std::string needle = lower_ascii(got);
  std::optional<std::size_t> best;
  std::size_t best_distance = kMaxDistance + 1;
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    const std::string candidate = lower_ascii(candidates[i]);
    const std::size_t gap = candidate.size() > needle.size() ? candidate.size() - needle.size()
                                                             : needle.size() - candidate.size();
    if (candidate.size() > kMaxCompared || gap > kMaxDistance) continue;
    const std::size_t distance = edit_distance(needle, candidate);
    if (distance < best_distance && distance < candidate.size()) {
      best = i;
      best_distance = distance;
    }
  }
  if (!best) return "";
  return " \u2014 did you mean " + quote(candidates[*best]) + "?";
}

}  // namespace gearsph::jsonschema::wording
