// GCC 12 reports a false -Wmaybe-uninitialized inside libstdc++'s <regex>
// (std::function in its NFA states) when building with sanitizers.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include "solver/job/json_schema.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <map>
#include <optional>
#include <regex>
#include <set>
#include <stdexcept>
#include <string_view>
#include <unordered_map>
#include <utility>
#pragma GCC diagnostic pop

namespace gearsph::jsonschema {
namespace {

using json = nlohmann::json;

// Instances nested deeper than this are reported instead of walked.
constexpr int kMaxInstanceDepth = 200;
// Schema evaluations stacked on one value (recursive $ref through allOf and
// friends without descending into the instance) before giving up.
constexpr int kMaxSchemaFrames = 1000;
// Schema evaluations allowed per call: a base plus an allowance per value in
// the instance. Only schemas whose recursion branches (anyOf of two $refs to
// themselves) get near it; they would otherwise take exponential time.
constexpr long kBaseSteps = 1'000'000;
constexpr long kStepsPerValue = 64;
// libstdc++'s regex executor recurses once per character: longer subjects
// could overflow the stack, so they are not matched.
constexpr std::size_t kMaxRegexSubject = 1000;
// Schema nesting accepted at construction (compilation is recursive too).
constexpr int kMaxSchemaNesting = 500;
// Errors kept while validating, before sorting and truncation.
constexpr std::size_t kErrorCap = 10'000;
// Values shown in messages are abbreviated beyond this many characters.
constexpr std::size_t kShortValue = 40;
// Lists in messages (enum values, known fields) are cut after this many.
constexpr std::size_t kMaxListed = 25;

const char* const kTooComplexMessage = "could not be checked completely: the schema is too complex";

// ---------------------------------------------------------------- text helpers

std::string dump(const json& value) {
  // `replace` because instances built in code may hold invalid UTF-8.
  return value.dump(-1, ' ', false, json::error_handler_t::replace);
}

bool is_continuation_byte(char c) {
  return (static_cast<unsigned char>(c) & 0xC0) == 0x80;
}

std::size_t count_code_points(const std::string& s) {
  return static_cast<std::size_t>(
      std::count_if(s.begin(), s.end(), [](char c) { return !is_continuation_byte(c); }));
}

// The first `n` code points of `s`.
std::string utf8_prefix(const std::string& s, std::size_t n) {
  std::size_t seen = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (!is_continuation_byte(s[i]) && seen++ == n) return s.substr(0, i);
  }
  return s;
}

std::string plural(std::size_t n, const std::string& noun) {
  return std::to_string(n) + " " + noun + (n == 1 ? "" : "s");
}

std::string quote(const std::string& s) {
  return dump(json(s));
}

std::string join(const std::vector<std::string>& parts, const std::string& separator) {
  std::string out;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    if (i > 0) out += separator;
    out += parts[i];
  }
  return out;
}

// "a", "a or b", "a, b or c" (or "and").
std::string join_words(const std::vector<std::string>& parts, const std::string& conjunction) {
  if (parts.size() <= 1) return join(parts, "");
  std::vector<std::string> head(parts.begin(), parts.end() - 1);
  return join(head, ", ") + " " + conjunction + " " + parts.back();
}

std::string join_or(const std::vector<std::string>& parts) {
  return join_words(parts, "or");
}

// Joins with ", ", cutting long lists short.
std::string join_listed(const std::vector<std::string>& parts) {
  if (parts.size() <= kMaxListed) return join(parts, ", ");
  std::vector<std::string> head(parts.begin(), parts.begin() + kMaxListed);
  return join(head, ", ") + " and " + std::to_string(parts.size() - kMaxListed) + " more";
}

// Shortest text that reads back as the same double: "4e-08", "0.353",
// "1000", "1.73e+11". Fixed notation is kept for 1e-4 <= |v| < 1e-3, where
// the shortest form would be the less readable "1e-04".
std::string format_double(double v) {
  char buf[64];
  const double magnitude = std::fabs(v);
  const bool prefer_fixed = magnitude >= 1e-4 && magnitude < 1e-3;
  const auto result = prefer_fixed
                          ? std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed)
                          : std::to_chars(buf, buf + sizeof buf, v);
  return result.ec == std::errc() ? std::string(buf, result.ptr) : "a number";
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

// Appends `v` in compact JSON to `out` unless that would exceed `budget`
// characters. Work is bounded by the budget and a small depth, whatever the
// size of `v` (json::dump would walk all of it, recursively).
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

// A value as shown in a message: numbers compactly, long strings and
// containers abbreviated.
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

// A required value (const or enum member) as shown in a message.
std::string expected_value(const json& v) {
  if (!v.is_structured() || short_json(v)) return describe_value(v);
  return "the required fixed " + std::string(v.is_array() ? "array" : "object");
}

// " (\"abc\")" after a kind, for values short enough to be worth repeating.
std::string value_suffix(const json& v) {
  if (v.is_string() || v.is_number() || v.is_boolean()) return " (" + describe_value(v) + ")";
  return "";
}

// ----------------------------------------------------------- did you mean

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

// " — did you mean \"plate\"?" when a candidate is within two edits (and
// not a complete rewrite of a very short word), else "".
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

// ----------------------------------------------------------------- numbers

bool is_integral(const json& v) {
  if (v.is_number_integer()) return true;  // also true for unsigned
  if (!v.is_number_float()) return false;
  const double x = v.get<double>();
  return std::isfinite(x) && std::floor(x) == x;
}

// Exact for two integers (signed or unsigned), through double otherwise.
int compare_numbers(const json& a, const json& b) {
  if (a.is_number_integer() && b.is_number_integer()) {
    const bool a_unsigned = a.is_number_unsigned(), b_unsigned = b.is_number_unsigned();
    if (!a_unsigned && !b_unsigned) {
      const auto x = a.get<std::int64_t>(), y = b.get<std::int64_t>();
      return (x > y) - (x < y);
    }
    if (!a_unsigned && a.get<std::int64_t>() < 0) return -1;
    if (!b_unsigned && b.get<std::int64_t>() < 0) return 1;
    const auto x = a.get<std::uint64_t>(), y = b.get<std::uint64_t>();
    return (x > y) - (x < y);
  }
  const double x = a.get<double>(), y = b.get<double>();
  return (x > y) - (x < y);
}

std::uint64_t magnitude(const json& integer) {
  if (integer.is_number_unsigned()) return integer.get<std::uint64_t>();
  const auto x = integer.get<std::int64_t>();
  return x < 0 ? 0 - static_cast<std::uint64_t>(x) : static_cast<std::uint64_t>(x);
}

bool is_multiple_of(const json& v, const json& divisor) {
  if (v.is_number_integer() && divisor.is_number_integer()) {
    return magnitude(v) % magnitude(divisor) == 0;
  }
  const double quotient = v.get<double>() / divisor.get<double>();
  if (!std::isfinite(quotient)) return true;  // too large to tell; do not reject
  // Division rounds, and its absolute error grows with the quotient.
  const double tolerance = 1e-9 + 1e-12 * std::fabs(quotient);
  return std::fabs(quotient - std::round(quotient)) <= tolerance;
}

// ----------------------------------------------------------- deep values
// json's own copy, comparison and dump recurse once per nesting level, so
// arbitrarily deep instances are measured or copied here without recursion.

// Whether `v` is or holds a container `limit` or more levels below itself.
bool nested_deeper_than(const json& v, int limit) {
  std::vector<std::pair<const json*, int>> todo{{&v, 0}};
  while (!todo.empty()) {
    const auto [value, depth] = todo.back();
    todo.pop_back();
    if (!value->is_structured()) continue;
    if (depth >= limit) return true;
    for (const auto& element : *value) todo.emplace_back(&element, depth + 1);
  }
  return false;
}

json deep_copy(const json& source) {
  json result;
  std::vector<std::pair<const json*, json*>> todo{{&source, &result}};
  while (!todo.empty()) {
    const auto [from, to] = todo.back();
    todo.pop_back();
    if (from->is_array()) {
      // Sized before children are queued, so their addresses stay valid.
      *to = json::array();
      to->get_ref<json::array_t&>().resize(from->size());
      for (std::size_t i = 0; i < from->size(); ++i) todo.emplace_back(&(*from)[i], &(*to)[i]);
    } else if (from->is_object()) {
      *to = json::object();  // std::map: inserted members never move
      for (auto it = from->begin(); it != from->end(); ++it) {
        todo.emplace_back(&it.value(), &(*to)[it.key()]);
      }
    } else {
      *to = *from;
    }
  }
  return result;
}

long step_budget(const json& instance) {
  long values = 0;
  std::vector<const json*> todo{&instance};
  while (!todo.empty()) {
    const json* value = todo.back();
    todo.pop_back();
    ++values;
    if (value->is_structured()) {
      for (const auto& element : *value) todo.push_back(&element);
    }
  }
  return kBaseSteps + kStepsPerValue * values;
}

// ------------------------------------------------------------------- types

enum TypeBit : unsigned {
  kObject = 1,
  kArray = 2,
  kString = 4,
  kNumber = 8,
  kInteger = 16,
  kBoolean = 32,
  kNull = 64,
};

struct TypeName {
  TypeBit bit;
  const char* name;    // as spelled in a schema
  const char* phrase;  // as said in a message
};

// In the order types are listed in messages.
constexpr TypeName kTypeNames[] = {
    {kObject, "object", "an object"},
    {kArray, "array", "an array"},
    {kString, "string", "a string"},
    {kNumber, "number", "a number"},
    {kInteger, "integer", "an integer"},
    {kBoolean, "boolean", "a boolean"},
    {kNull, "null", "null"},
};

bool has_type(const json& v, unsigned types) {
  switch (v.type()) {
    case json::value_t::null:
      return types & kNull;
    case json::value_t::boolean:
      return types & kBoolean;
    case json::value_t::string:
      return types & kString;
    case json::value_t::array:
      return types & kArray;
    case json::value_t::object:
      return types & kObject;
    case json::value_t::number_integer:
    case json::value_t::number_unsigned:
    case json::value_t::number_float:
      return (types & kNumber) || ((types & kInteger) && is_integral(v));
    default:
      return false;
  }
}

std::vector<std::string> type_phrases(unsigned types) {
  if (types & kNumber) types &= ~static_cast<unsigned>(kInteger);  // integers are numbers
  std::vector<std::string> phrases;
  for (const auto& t : kTypeNames) {
    if (types & t.bit) phrases.emplace_back(t.phrase);
  }
  return phrases;
}

// --------------------------------------------------------- compiled schema

struct Pattern {
  std::string source;
  std::regex regex;
};

// Whether `pattern` occurs in `s`; nullopt when it cannot be decided safely.
std::optional<bool> search(const Pattern& pattern, const std::string& s) {
  if (s.size() > kMaxRegexSubject) return std::nullopt;
  try {
    return std::regex_search(s, pattern.regex);
  } catch (const std::exception&) {  // e.g. regex_error(error_complexity)
    return std::nullopt;
  }
}

struct Node;

struct PatternSchema {
  Pattern pattern;
  const Node* schema;
};

// One schema object with its keywords parsed. Absent keywords are null or
// empty. Pointers refer to nodes and JSON owned by the same Compiled.
struct Node {
  std::string location;  // JSON pointer of this schema in the root schema
  const json* raw = nullptr;
  std::optional<bool> boolean;   // set for the schemas `true` and `false`
  const Node* ref = nullptr;     // the schema "$ref" names
  const Node* target = nullptr;  // the end of the chain of $refs that starts here

  unsigned types = 0;  // TypeBit mask; 0 when "type" is absent
  const json* enum_values = nullptr;
  const json* const_value = nullptr;

  const json* minimum = nullptr;
  const json* maximum = nullptr;
  const json* exclusive_minimum = nullptr;
  const json* exclusive_maximum = nullptr;
  const json* multiple_of = nullptr;

  std::optional<std::size_t> min_length, max_length;
  std::optional<Pattern> pattern;

  const Node* items = nullptr;                    // single-schema form
  std::optional<std::vector<const Node*>> tuple;  // array form of "items"
  const Node* additional_items = nullptr;
  std::optional<std::size_t> min_items, max_items;
  bool unique_items = false;
  const Node* contains = nullptr;

  std::map<std::string, const Node*> properties;
  std::vector<std::string> required;
  std::vector<PatternSchema> pattern_properties;
  const Node* additional_properties = nullptr;
  const Node* property_names = nullptr;
  std::optional<std::size_t> min_properties, max_properties;

  std::vector<const Node*> all_of, any_of, one_of;
  const Node* not_schema = nullptr;
  const Node* if_schema = nullptr;
  const Node* then_schema = nullptr;
  const Node* else_schema = nullptr;
};

const json* member(const json& object, const char* key) {
  const auto it = object.find(key);
  return it == object.end() ? nullptr : &*it;
}

// The schema that applies in place of `node`: the end of its $ref chain.
const Node* resolve(const Node* node) {
  return node->ref ? node->target : node;
}

bool is_false_schema(const Node* node) {
  return node && resolve(node)->boolean == false;
}
// The "default" of a property's schema, looking through $refs.
const json* find_default(const Node* node) {
  for (; node; node = node->ref) {  // chains end: loops are rejected
    if (node->raw->is_object()) {
      if (const json* d = member(*node->raw, "default")) return d;
    }
  }
  return nullptr;
}

// A schema's title, else a short description, for naming oneOf branches.
std::optional<std::string> label_of(const Node* node) {
  constexpr std::size_t kMaxLabel = 60;
  for (; node; node = node->ref) {  // chains end: loops are rejected
    if (!node->raw->is_object()) return std::nullopt;
    for (const char* key : {"title", "description"}) {
      const json* text = member(*node->raw, key);
      if (text && text->is_string() && text->get_ref<const std::string&>().size() <= kMaxLabel) {
        return text->get<std::string>();
      }
    }
  }
  return std::nullopt;
}

// Calls fn(schema) for the "properties" and "patternProperties" entries that
// apply to member `key`; returns whether there was any.
template <class Fn>
bool for_each_member_schema(const Node& node, const std::string& key, Fn&& fn) {
  bool matched = false;
  if (const auto it = node.properties.find(key); it != node.properties.end()) {
    matched = true;
    fn(*it->second);
  }
  for (const auto& entry : node.pattern_properties) {
    if (search(entry.pattern, key).value_or(false)) {
      matched = true;
      fn(*entry.schema);
    }
  }
  return matched;
}

// -------------------------------------------------------------- compiler

[[noreturn]] void fail(const std::string& location, const std::string& what) {
  throw std::invalid_argument("invalid JSON schema at #" + location + ": " + what);
}

std::optional<std::string> unescape_token(const std::string& token) {
  std::string out;
  for (std::size_t i = 0; i < token.size(); ++i) {
    if (token[i] != '~') {
      out += token[i];
    } else if (i + 1 < token.size() && (token[i + 1] == '0' || token[i + 1] == '1')) {
      out += token[++i] == '0' ? '~' : '/';
    } else {
      return std::nullopt;
    }
  }
  return out;
}

int hex_digit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

// A $ref is a URI, so its fragment may be percent-encoded ("%25" for '%').
std::optional<std::string> percent_decode(const std::string& s) {
  std::string out;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i] != '%') {
      out += s[i];
      continue;
    }
    if (i + 2 >= s.size()) return std::nullopt;
    const int hi = hex_digit(s[i + 1]), lo = hex_digit(s[i + 2]);
    if (hi < 0 || lo < 0) return std::nullopt;
    out += static_cast<char>(hi * 16 + lo);
    i += 2;
  }
  return out;
}

std::optional<std::size_t> parse_index(const std::string& token) {
  if (token.empty() || token.size() > 9 || (token.size() > 1 && token[0] == '0')) {
    return std::nullopt;
  }
  std::size_t index = 0;
  for (char c : token) {
    if (c < '0' || c > '9') return std::nullopt;
    index = index * 10 + static_cast<std::size_t>(c - '0');
  }
  return index;
}

std::vector<std::string> split_pointer(const std::string& pointer) {
  std::vector<std::string> tokens;
  std::size_t start = 1;  // skip the leading '/'
  while (true) {
    const std::size_t slash = pointer.find('/', start);
    tokens.push_back(pointer.substr(start, slash - start));
    if (slash == std::string::npos) return tokens;
    start = slash + 1;
  }
}

class Compiler {
 public:
  Compiler(const json& root, std::vector<std::unique_ptr<Node>>& nodes)
      : root_(root), nodes_(nodes) {}

  const Node* compile_root() {
    const Node* root = compile(root_, "", 0);
    resolve_ref_chains();
    return root;
  }

 private:
  const Node* compile(const json& schema, const std::string& location, int nesting);
  const Node* child(const Node& parent, const json& schema, const std::string& suffix,
                    int nesting) {
    return compile(schema, parent.location + suffix, nesting + 1);
  }
  const Node* keyword_schema(const Node& n, const json& s, const char* key, int nesting);
  std::vector<const Node*> schema_list(const Node& n, const json& s, const char* key, int nesting);

  void compile_keywords(Node& n, const json& s, int nesting);
  void compile_definitions(const Node& n, const json& s, int nesting);
  const Node* resolve_ref(const Node& n, const json& ref, int nesting);
  void compile_values(Node& n, const json& s);
  void compile_numeric(Node& n, const json& s);
  void compile_string(Node& n, const json& s);
  void compile_array(Node& n, const json& s, int nesting);
  void compile_object(Node& n, const json& s, int nesting);
  void compile_properties(Node& n, const json& s, int nesting);
  void compile_combinators(Node& n, const json& s, int nesting);
  void resolve_ref_chains();

  const json* number_keyword(const Node& n, const json& s, const char* key) const;
  std::optional<std::size_t> count_keyword(const Node& n, const json& s, const char* key) const;
  Pattern compile_pattern(const Node& n, const std::string& source) const;

  const json& root_;
  std::vector<std::unique_ptr<Node>>& nodes_;
  std::unordered_map<std::string, Node*> by_location_;  // so shared targets compile once
};

const Node* Compiler::compile(const json& schema, const std::string& location, int nesting) {
  if (const auto it = by_location_.find(location); it != by_location_.end()) return it->second;
  if (nesting > kMaxSchemaNesting) fail(location, "the schema is nested too deeply");
  nodes_.push_back(std::make_unique<Node>());
  Node& n = *nodes_.back();
  n.location = location;
  n.raw = &schema;
  by_location_.emplace(location, &n);  // before the children, so cycles terminate
  if (schema.is_boolean()) {
    n.boolean = schema.get<bool>();
  } else if (schema.is_object()) {
    compile_keywords(n, schema, nesting);
  } else {
    fail(location, "a schema must be an object or a boolean, not " + kind_of(schema));
  }
  return &n;
}

void Compiler::compile_keywords(Node& n, const json& s, int nesting) {
  if (const json* definitions = member(s, "definitions")) {
    compile_definitions(n, *definitions, nesting);
  }
  if (const json* ref = member(s, "$ref")) {
    n.ref = resolve_ref(n, *ref, nesting);
    return;  // draft-07: keywords next to "$ref" are ignored
  }
  compile_values(n, s);
  compile_numeric(n, s);
  compile_string(n, s);
  compile_array(n, s, nesting);
  compile_object(n, s, nesting);
  compile_combinators(n, s, nesting);
}

void Compiler::compile_definitions(const Node& n, const json& definitions, int nesting) {
  if (!definitions.is_object()) fail(n.location, "\"definitions\" must be an object");
  for (const auto& [name, schema] : definitions.items()) {
    child(n, schema, "/definitions/" + escape_pointer_token(name), nesting);
  }
}

const Node* Compiler::resolve_ref(const Node& n, const json& ref, int nesting) {
  if (!ref.is_string()) fail(n.location, "\"$ref\" must be a string");
  const auto& text = ref.get_ref<const std::string&>();
  const auto cannot = [&](const std::string& why) {
    fail(n.location, "cannot resolve \"$ref\": " + quote(text) + " (" + why + ")");
  };
  if (text.empty() || text[0] != '#') cannot("only references within this schema are supported");
  const std::optional<std::string> fragment = percent_decode(text.substr(1));
  if (!fragment) cannot("bad percent-encoding");
  if (fragment->empty()) return compile(root_, "", nesting + 1);
  if ((*fragment)[0] != '/') cannot("only JSON pointer fragments are supported");

  const json* target = &root_;
  std::string location;
  for (const std::string& raw_token : split_pointer(*fragment)) {
    const std::optional<std::string> token = unescape_token(raw_token);
    if (!token) cannot("bad escape in " + quote(raw_token));
    if (target->is_object() && target->contains(*token)) {
      target = &target->at(*token);
    } else if (const auto index = parse_index(*token);
               target->is_array() && index && *index < target->size()) {
      target = &target->at(*index);
    } else {
      cannot("nothing at " + quote(*token));
    }
    location += '/';  // two appends: "/" + temporary trips GCC 12's -Wrestrict at -O3
    location += escape_pointer_token(*token);
  }
  return compile(*target, location, nesting + 1);
}

void Compiler::compile_values(Node& n, const json& s) {
  if (const json* type = member(s, "type")) {
    const auto add = [&](const json& name) {
      for (const auto& t : kTypeNames) {
        if (name.is_string() && name.get_ref<const std::string&>() == t.name) {
          n.types |= t.bit;
          return;
        }
      }
      fail(n.location, "unknown type " + dump(name));
    };
    if (type->is_array() && !type->empty()) {
      for (const auto& name : *type) add(name);
    } else if (type->is_string()) {
      add(*type);
    } else {
      fail(n.location, "\"type\" must be a type name or a non-empty array of them");
    }
  }
  if (const json* values = member(s, "enum")) {
    if (!values->is_array()) fail(n.location, "\"enum\" must be an array");
    n.enum_values = values;
  }
  n.const_value = member(s, "const");
}

const json* Compiler::number_keyword(const Node& n, const json& s, const char* key) const {
  const json* value = member(s, key);
  if (value && !value->is_number()) fail(n.location, quote(key) + " must be a number");
  return value;
}

std::optional<std::size_t> Compiler::count_keyword(const Node& n, const json& s,
                                                   const char* key) const {
  const json* value = member(s, key);
  if (!value) return std::nullopt;
  if (value->is_number_unsigned()) return value->get<std::size_t>();
  if (value->is_number_integer() && value->get<std::int64_t>() >= 0) {
    return static_cast<std::size_t>(value->get<std::int64_t>());
  }
  // 3.0 is an integer too; the bound keeps the cast defined.
  if (value->is_number_float() && is_integral(*value) && value->get<double>() >= 0 &&
      value->get<double>() < 9e18) {
    return static_cast<std::size_t>(value->get<double>());
  }
  fail(n.location, quote(key) + " must be a non-negative integer");
}

Pattern Compiler::compile_pattern(const Node& n, const std::string& source) const {
  try {
    return Pattern{source, std::regex(source, std::regex::ECMAScript)};
  } catch (const std::regex_error& e) {
    fail(n.location, "invalid regular expression " + quote(source) + ": " + e.what());
  }
}

void Compiler::compile_numeric(Node& n, const json& s) {
  n.minimum = number_keyword(n, s, "minimum");
  n.maximum = number_keyword(n, s, "maximum");
  n.exclusive_minimum = number_keyword(n, s, "exclusiveMinimum");
  n.exclusive_maximum = number_keyword(n, s, "exclusiveMaximum");
  n.multiple_of = number_keyword(n, s, "multipleOf");
  if (n.multiple_of && n.multiple_of->get<double>() <= 0) {
    fail(n.location, "\"multipleOf\" must be greater than 0");
  }
}

void Compiler::compile_string(Node& n, const json& s) {
  n.min_length = count_keyword(n, s, "minLength");
  n.max_length = count_keyword(n, s, "maxLength");
  if (const json* pattern = member(s, "pattern")) {
    if (!pattern->is_string()) fail(n.location, "\"pattern\" must be a string");
    n.pattern = compile_pattern(n, pattern->get<std::string>());
  }
}

const Node* Compiler::keyword_schema(const Node& n, const json& s, const char* key, int nesting) {
  const json* schema = member(s, key);
  return schema ? child(n, *schema, "/" + std::string(key), nesting) : nullptr;
}

std::vector<const Node*> Compiler::schema_list(const Node& n, const json& s, const char* key,
                                               int nesting) {
  std::vector<const Node*> list;
  const json* schemas = member(s, key);
  if (!schemas) return list;
  if (!schemas->is_array() || schemas->empty()) {
    fail(n.location, quote(key) + " must be a non-empty array of schemas");
  }
  for (std::size_t i = 0; i < schemas->size(); ++i) {
    list.push_back(
        child(n, schemas->at(i), "/" + std::string(key) + "/" + std::to_string(i), nesting));
  }
  return list;
}

void Compiler::compile_array(Node& n, const json& s, int nesting) {
  if (const json* items = member(s, "items"); items && items->is_array()) {
    n.tuple.emplace();
    for (std::size_t i = 0; i < items->size(); ++i) {
      n.tuple->push_back(child(n, items->at(i), "/items/" + std::to_string(i), nesting));
    }
  } else {
    n.items = keyword_schema(n, s, "items", nesting);
  }
  n.additional_items = keyword_schema(n, s, "additionalItems", nesting);
  n.min_items = count_keyword(n, s, "minItems");
  n.max_items = count_keyword(n, s, "maxItems");
  if (const json* unique = member(s, "uniqueItems")) {
    if (!unique->is_boolean()) fail(n.location, "\"uniqueItems\" must be true or false");
    n.unique_items = unique->get<bool>();
  }
  n.contains = keyword_schema(n, s, "contains", nesting);
}

void Compiler::compile_properties(Node& n, const json& s, int nesting) {
  if (const json* properties = member(s, "properties")) {
    if (!properties->is_object()) fail(n.location, "\"properties\" must be an object");
    for (const auto& [name, schema] : properties->items()) {
      n.properties[name] = child(n, schema, "/properties/" + escape_pointer_token(name), nesting);
    }
  }
  if (const json* patterns = member(s, "patternProperties")) {
    if (!patterns->is_object()) fail(n.location, "\"patternProperties\" must be an object");
    for (const auto& [source, schema] : patterns->items()) {
      const Node* compiled =
          child(n, schema, "/patternProperties/" + escape_pointer_token(source), nesting);
      n.pattern_properties.push_back({compile_pattern(n, source), compiled});
    }
  }
}

void Compiler::compile_object(Node& n, const json& s, int nesting) {
  compile_properties(n, s, nesting);
  if (const json* required = member(s, "required")) {
    if (!required->is_array()) fail(n.location, "\"required\" must be an array of strings");
    for (const auto& name : *required) {
      if (!name.is_string()) fail(n.location, "\"required\" must be an array of strings");
      n.required.push_back(name.get<std::string>());
    }
  }
  n.additional_properties = keyword_schema(n, s, "additionalProperties", nesting);
  n.property_names = keyword_schema(n, s, "propertyNames", nesting);
  n.min_properties = count_keyword(n, s, "minProperties");
  n.max_properties = count_keyword(n, s, "maxProperties");
}

void Compiler::compile_combinators(Node& n, const json& s, int nesting) {
  n.all_of = schema_list(n, s, "allOf", nesting);
  n.any_of = schema_list(n, s, "anyOf", nesting);
  n.one_of = schema_list(n, s, "oneOf", nesting);
  n.not_schema = keyword_schema(n, s, "not", nesting);
  n.if_schema = keyword_schema(n, s, "if", nesting);
  n.then_schema = keyword_schema(n, s, "then", nesting);
  n.else_schema = keyword_schema(n, s, "else", nesting);
}

// Points every $ref node at the end of its chain of $refs. A chain that
// loops back on itself never reaches a schema to check against.
void Compiler::resolve_ref_chains() {
  for (const auto& start : nodes_) {
    const Node* node = start.get();
    for (std::size_t hops = 0; node->ref; ++hops, node = node->ref) {
      if (hops > nodes_.size()) fail(start->location, "\"$ref\" refers to itself in a loop");
    }
    if (start->ref) start->target = node;
  }
}

// -------------------------------------------------------------- evaluation

// How an issue came about, so anyOf/oneOf can merge "wrong kind of value"
// failures of all their branches into one message.
enum class IssueKind { kOther, kType, kValue };

struct Issue {
  std::string pointer;
  std::string message;
  IssueKind kind = IssueKind::kOther;
  std::vector<std::string> expected;    // accepted types or values, as phrases
  std::vector<std::string> candidates;  // accepted strings, for did-you-mean
};

// Collects issues. In `first_only` mode (a yes/no question such as "does
// the `if` schema match?") checks stop at the first issue.
class Sink {
 public:
  explicit Sink(bool first_only) : first_only_(first_only) {}

  void add(Issue issue) {
    if (issues_.size() < kErrorCap) issues_.push_back(std::move(issue));
  }
  void add(const std::string& pointer, std::string message) {
    add(Issue{pointer, std::move(message), IssueKind::kOther, {}, {}});
  }
  void append(std::vector<Issue>& more) {
    for (auto& issue : more) add(std::move(issue));
  }
  bool done() const { return (first_only_ && !issues_.empty()) || issues_.size() >= kErrorCap; }
  bool first_only() const { return first_only_; }
  bool empty() const { return issues_.empty(); }
  std::vector<Issue>& issues() { return issues_; }

 private:
  bool first_only_;
  std::vector<Issue> issues_;
};

// Counts nested schema evaluations for the recursion limit.
class FrameGuard {
 public:
  explicit FrameGuard(int& frames) : frames_(frames) { ++frames_; }
  ~FrameGuard() { --frames_; }
  FrameGuard(const FrameGuard&) = delete;
  FrameGuard& operator=(const FrameGuard&) = delete;
  bool too_deep() const { return frames_ > kMaxSchemaFrames; }

 private:
  int& frames_;
};

std::string child_pointer(const std::string& pointer, const std::string& key) {
  return pointer + "/" + escape_pointer_token(key);
}

std::string child_pointer(const std::string& pointer, std::size_t index) {
  return pointer + "/" + std::to_string(index);
}

// "must be a number, not a string (\"abc\")"; for a fractional number where
// only integers are accepted: "must be an integer (got 3.5)".
std::string type_message(const std::vector<std::string>& expected, const json& v) {
  const std::string head = "must be " + join_or(expected);
  if (v.is_number()) {
    const bool integer_expected =
        std::find(expected.begin(), expected.end(), "an integer") != expected.end();
    if (integer_expected) return head + " (got " + describe_value(v) + ")";
  }
  return head + ", not " + kind_of(v) + value_suffix(v);
}

std::vector<std::string> value_phrases(const json& values) {
  std::vector<std::string> phrases;
  for (const auto& value : values) phrases.push_back(expected_value(value));
  return phrases;
}

std::vector<std::string> string_values(const json& values) {
  std::vector<std::string> strings;
  for (const auto& value : values) {
    if (value.is_string()) strings.push_back(value.get<std::string>());
  }
  return strings;
}

// "must be \"a\" (got ...)" or "must be one of \"a\", \"b\" (got ...)",
// with a suggestion when the value is a near miss.
std::string value_message(const std::vector<std::string>& expected,
                          const std::vector<std::string>& candidates, const json& v) {
  if (expected.empty()) return "is not allowed here: no value is accepted";  // "enum": []
  std::string message = expected.size() == 1 ? "must be " + expected.front()
                                             : "must be one of " + join_listed(expected);
  message += " (got " + describe_value(v) + ")";
  if (v.is_string()) message += did_you_mean(v.get_ref<const std::string&>(), candidates);
  return message;
}

// A short phrase for what a schema accepts ("a string", "3", "one of 1, 2"), used
// by "not" and "contains"; nullopt when there is no brief way to say it.
std::optional<std::string> accepted_phrase(const Node* node) {
  node = resolve(node);
  if (node->boolean) return std::nullopt;
  if (node->const_value) return expected_value(*node->const_value);
  if (node->enum_values) {
    if (node->enum_values->size() == 1) return expected_value(node->enum_values->at(0));
    return "one of " + join_listed(value_phrases(*node->enum_values));
  }
  if (node->types) return join_or(type_phrases(node->types));
  return std::nullopt;
}

// The message builders below are noinline: their string temporaries would
// otherwise enlarge the frames of the recursive evaluation path.

[[gnu::noinline]] void report_missing_item(const Node& wanted, const json& v,
                                           const std::string& ptr, Sink& sink) {
  const std::optional<std::string> phrase = accepted_phrase(&wanted);
  std::string message = phrase ? "must contain at least one item that is " + *phrase
                               : "must contain at least one item of the required form";
  if (v.empty()) message += " (it is empty)";
  sink.add(ptr, message);
}

[[gnu::noinline]] void report_ambiguous(const std::vector<const Node*>& matched,
                                        const std::string& ptr, Sink& sink) {
  std::vector<std::string> labels;
  for (const Node* branch : matched) {
    if (const auto label = label_of(branch)) labels.push_back(quote(*label));
  }
  std::string message = "matches more than one of the allowed forms";
  if (labels.size() == matched.size()) message += " (" + join_or(labels) + ")";
  sink.add(ptr, message);
}

[[gnu::noinline]] void report_excluded(const Node& excluded, const std::string& ptr, Sink& sink) {
  const Node* resolved = resolve(&excluded);
  if (const std::optional<std::string> phrase = accepted_phrase(resolved)) {
    sink.add(ptr, "must not be " + *phrase);
  } else if (!resolved->required.empty()) {  // the idiom for forbidden fields
    std::vector<std::string> names;
    for (const auto& name : resolved->required) names.push_back(quote(name));
    sink.add(ptr, std::string(names.size() == 1 ? "must not have the field "
                                                : "must not have all of the fields ") +
                      join_words(names, "and"));
  } else if (const auto label = label_of(&excluded)) {
    sink.add(ptr, "must not match " + quote(*label));
  } else {
    sink.add(ptr, "must not match the excluded form");
  }
}

class Evaluator {
 public:
  explicit Evaluator(long max_steps) : max_steps_(max_steps) {}
  void check(const Node& node, const json& v, const std::string& ptr, int depth, Sink& sink);
  bool matches(const Node& node, const json& v, const std::string& ptr, int depth) {
    Sink quick(true);
    check(node, v, ptr, depth, quick);
    return quick.empty();
  }
  bool exhausted() const { return exhausted_; }

 private:
  enum class Limit { kFalseSchema, kTooComplex, kSchemaTooDeep, kInstanceTooDeep };

  // Functions marked noinline build messages in string temporaries; kept out
  // of line, those do not enlarge the frames of the recursive path
  // (check -> check_keywords -> container checks -> check), which matters
  // most under AddressSanitizer.
  [[gnu::noinline]] void report(Limit limit, const std::string& ptr, Sink& sink);
  void check_keywords(const Node& n, const json& v, const std::string& ptr, int depth, Sink& sink);
  void descend(const Node& node, const json& v, const std::string& ptr, int depth, Sink& sink);
  [[gnu::noinline]] bool check_type(const Node& n, const json& v, const std::string& ptr,
                                    Sink& sink);
  [[gnu::noinline]] void check_values(const Node& n, const json& v, const std::string& ptr,
                                      Sink& sink);
  [[gnu::noinline]] void check_number(const Node& n, const json& v, const std::string& ptr,
                                      Sink& sink);
  [[gnu::noinline]] void check_string(const Node& n, const json& v, const std::string& ptr,
                                      Sink& sink);
  void check_array(const Node& n, const json& v, const std::string& ptr, int depth, Sink& sink);
  void check_items(const Node& n, const json& v, const std::string& ptr, int depth, Sink& sink);
  [[gnu::noinline]] void check_unique(const json& v, const std::string& ptr, int depth, Sink& sink);
  void check_contains(const Node& n, const json& v, const std::string& ptr, int depth, Sink& sink);
  void check_object(const Node& n, const json& v, const std::string& ptr, int depth, Sink& sink);
  void check_members(const Node& n, const json& v, const std::string& ptr, int depth, Sink& sink);
  [[gnu::noinline]] void report_unknown(const Node& n, const std::string& key,
                                        const std::string& ptr, Sink& sink);
  void check_property_names(const Node& n, const json& v, const std::string& ptr, int depth,
                            Sink& sink);
  void check_combinators(const Node& n, const json& v, const std::string& ptr, int depth,
                         Sink& sink);
  void check_any_of(const Node& n, const json& v, const std::string& ptr, int depth, Sink& sink);
  void check_one_of(const Node& n, const json& v, const std::string& ptr, int depth, Sink& sink);
  void check_not(const Node& n, const json& v, const std::string& ptr, int depth, Sink& sink);
  [[gnu::noinline]] void report_closest(std::vector<std::vector<Issue>>& failures, const json& v,
                                        const std::string& ptr, Sink& sink);

  const long max_steps_;
  int frames_ = 0;
  long steps_ = 0;
  bool exhausted_ = false;
};

void Evaluator::check(const Node& node, const json& v, const std::string& ptr, int depth,
                      Sink& sink) {
  const Node& target = *resolve(&node);  // no frame per $ref
  if (target.boolean) {
    if (!*target.boolean) report(Limit::kFalseSchema, ptr, sink);
    return;
  }
  if (++steps_ > max_steps_) exhausted_ = true;
  if (exhausted_) {  // every check fails from now on, so nothing passes by accident
    report(Limit::kTooComplex, ptr, sink);
    return;
  }
  const FrameGuard frame(frames_);
  if (frame.too_deep()) {
    report(Limit::kSchemaTooDeep, ptr, sink);
    return;
  }
  check_keywords(target, v, ptr, depth, sink);
}

void Evaluator::report(Limit limit, const std::string& ptr, Sink& sink) {
  switch (limit) {
    case Limit::kFalseSchema:
      sink.add(ptr, "is not allowed here");
      return;
    case Limit::kTooComplex:
      sink.add(ptr, kTooComplexMessage);
      return;
    case Limit::kSchemaTooDeep:
      sink.add(ptr, "is nested too deeply: the schema refers to itself more than " +
                        std::to_string(kMaxSchemaFrames) + " times here");
      return;
    case Limit::kInstanceTooDeep:
      sink.add(ptr,
               "is nested too deeply (more than " + std::to_string(kMaxInstanceDepth) + " levels)");
      return;
  }
}

void Evaluator::check_keywords(const Node& n, const json& v, const std::string& ptr, int depth,
                               Sink& sink) {
  // After a type mismatch the other keywords would only repeat it.
  if (!check_type(n, v, ptr, sink)) return;
  check_values(n, v, ptr, sink);
  if (sink.done()) return;
  if (v.is_number()) check_number(n, v, ptr, sink);
  if (v.is_string()) check_string(n, v, ptr, sink);
  if (v.is_array()) check_array(n, v, ptr, depth, sink);
  if (v.is_object()) check_object(n, v, ptr, depth, sink);
  if (sink.done()) return;
  check_combinators(n, v, ptr, depth, sink);
}

// Checks a value inside `v`'s container: one level deeper.
void Evaluator::descend(const Node& node, const json& v, const std::string& ptr, int depth,
                        Sink& sink) {
  if (depth >= kMaxInstanceDepth) {
    report(Limit::kInstanceTooDeep, ptr, sink);
    return;
  }
  check(node, v, ptr, depth + 1, sink);
}

bool Evaluator::check_type(const Node& n, const json& v, const std::string& ptr, Sink& sink) {
  if (!n.types || has_type(v, n.types)) return true;
  std::vector<std::string> expected = type_phrases(n.types);
  std::string message = type_message(expected, v);
  sink.add(Issue{ptr, std::move(message), IssueKind::kType, std::move(expected), {}});
  return false;
}

void Evaluator::check_values(const Node& n, const json& v, const std::string& ptr, Sink& sink) {
  if (n.const_value && v != *n.const_value) {
    std::vector<std::string> expected{expected_value(*n.const_value)};
    std::vector<std::string> candidates = string_values(json::array({*n.const_value}));
    std::string message = value_message(expected, candidates, v);
    sink.add(Issue{ptr, std::move(message), IssueKind::kValue, std::move(expected),
                   std::move(candidates)});
  }
  if (n.enum_values &&
      std::find(n.enum_values->begin(), n.enum_values->end(), v) == n.enum_values->end()) {
    std::vector<std::string> expected = value_phrases(*n.enum_values);
    std::vector<std::string> candidates = string_values(*n.enum_values);
    std::string message = value_message(expected, candidates, v);
    sink.add(Issue{ptr, std::move(message), IssueKind::kValue, std::move(expected),
                   std::move(candidates)});
  }
}

void Evaluator::check_number(const Node& n, const json& v, const std::string& ptr, Sink& sink) {
  const std::string got = " (got " + format_number(v) + ")";
  if (n.minimum && compare_numbers(v, *n.minimum) < 0) {
    sink.add(ptr, "must be at least " + format_number(*n.minimum) + got);
  }
  if (n.exclusive_minimum && compare_numbers(v, *n.exclusive_minimum) <= 0) {
    sink.add(ptr, "must be greater than " + format_number(*n.exclusive_minimum) + got);
  }
  if (n.maximum && compare_numbers(v, *n.maximum) > 0) {
    sink.add(ptr, "must be at most " + format_number(*n.maximum) + got);
  }
  if (n.exclusive_maximum && compare_numbers(v, *n.exclusive_maximum) >= 0) {
    sink.add(ptr, "must be less than " + format_number(*n.exclusive_maximum) + got);
  }
  if (n.multiple_of && !is_multiple_of(v, *n.multiple_of)) {
    sink.add(ptr, "must be a multiple of " + format_number(*n.multiple_of) + got);
  }
}

void Evaluator::check_string(const Node& n, const json& v, const std::string& ptr, Sink& sink) {
  const auto& s = v.get_ref<const std::string&>();
  const std::size_t length = count_code_points(s);
  if (n.min_length && length < *n.min_length) {
    sink.add(ptr, length == 0
                      ? "must not be empty (at least " + plural(*n.min_length, "character") + ")"
                      : "must be at least " + plural(*n.min_length, "character") + " long (got " +
                            describe_value(v) + ")");
  }
  if (n.max_length && length > *n.max_length) {
    sink.add(ptr, "must be at most " + plural(*n.max_length, "character") + " long (got " +
                      plural(length, "character") + ")");
  }
  if (n.pattern) {
    const std::optional<bool> found = search(*n.pattern, s);
    const std::string pattern = quote(n.pattern->source);
    if (!found && s.size() > kMaxRegexSubject) {
      sink.add(ptr, "is too long to check against the pattern " + pattern + " (more than " +
                        std::to_string(kMaxRegexSubject) + " bytes)");
    } else if (!found) {  // the regex engine gave up
      sink.add(ptr, "could not be checked against the pattern " + pattern);
    } else if (!*found) {
      sink.add(ptr, "must match the pattern " + pattern + " (got " + describe_value(v) + ")");
    }
  }
}

void Evaluator::check_array(const Node& n, const json& v, const std::string& ptr, int depth,
                            Sink& sink) {
  if (n.min_items && v.size() < *n.min_items) {
    sink.add(ptr, v.empty() ? "must not be empty (at least " + plural(*n.min_items, "item") + ")"
                            : "must have at least " + plural(*n.min_items, "item") + " (got " +
                                  std::to_string(v.size()) + ")");
  }
  if (n.max_items && v.size() > *n.max_items) {
    sink.add(ptr, "must have at most " + plural(*n.max_items, "item") + " (got " +
                      std::to_string(v.size()) + ")");
  }
  if (n.unique_items) check_unique(v, ptr, depth, sink);
  check_items(n, v, ptr, depth, sink);
  if (n.contains) check_contains(n, v, ptr, depth, sink);
}

void Evaluator::check_items(const Node& n, const json& v, const std::string& ptr, int depth,
                            Sink& sink) {
  if (n.items) {
    for (std::size_t i = 0; i < v.size() && !sink.done(); ++i) {
      descend(*n.items, v[i], child_pointer(ptr, i), depth, sink);
    }
    return;
  }
  if (!n.tuple) return;
  const std::size_t fixed = std::min(v.size(), n.tuple->size());
  for (std::size_t i = 0; i < fixed && !sink.done(); ++i) {
    descend(*(*n.tuple)[i], v[i], child_pointer(ptr, i), depth, sink);
  }
  if (v.size() <= fixed || !n.additional_items) return;
  if (is_false_schema(n.additional_items)) {
    // Same wording as maxItems, so the two collapse into one error.
    sink.add(ptr, "must have at most " + plural(fixed, "item") + " (got " +
                      std::to_string(v.size()) + ")");
    return;
  }
  for (std::size_t i = fixed; i < v.size() && !sink.done(); ++i) {
    descend(*n.additional_items, v[i], child_pointer(ptr, i), depth, sink);
  }
}

// Sorting finds duplicates in n log n; json's ordering treats 1 and 1.0 as
// equivalent, like its equality and like JSON Schema.
void Evaluator::check_unique(const json& v, const std::string& ptr, int depth, Sink& sink) {
  if (nested_deeper_than(v, kMaxInstanceDepth - depth)) {  // json's == and < recurse
    report(Limit::kInstanceTooDeep, ptr, sink);
    return;
  }
  std::vector<std::size_t> order(v.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return v[a] < v[b]; });
  std::vector<std::pair<std::size_t, std::size_t>> duplicates;  // (later index, first index)
  std::size_t first = 0;
  for (std::size_t k = 1; k < order.size(); ++k) {
    if (v[order[k]] == v[order[first]]) {
      duplicates.emplace_back(order[k], order[first]);
    } else {
      first = k;
    }
  }
  std::sort(duplicates.begin(), duplicates.end());
  for (const auto& [later, original] : duplicates) {
    if (sink.done()) return;
    sink.add(child_pointer(ptr, later),
             "repeats item " + std::to_string(original) + "; all items must be different");
  }
}

void Evaluator::check_contains(const Node& n, const json& v, const std::string& ptr, int depth,
                               Sink& sink) {
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (depth < kMaxInstanceDepth && matches(*n.contains, v[i], child_pointer(ptr, i), depth + 1))
      return;
  }
  report_missing_item(*n.contains, v, ptr, sink);
}

void Evaluator::check_object(const Node& n, const json& v, const std::string& ptr, int depth,
                             Sink& sink) {
  if (n.min_properties && v.size() < *n.min_properties) {
    sink.add(ptr, "must have at least " + plural(*n.min_properties, "field") + " (got " +
                      std::to_string(v.size()) + ")");
  }
  if (n.max_properties && v.size() > *n.max_properties) {
    sink.add(ptr, "must have at most " + plural(*n.max_properties, "field") + " (got " +
                      std::to_string(v.size()) + ")");
  }
  for (const auto& name : n.required) {
    if (!v.contains(name)) sink.add(child_pointer(ptr, name), "is required");
  }
  if (n.property_names) check_property_names(n, v, ptr, depth, sink);
  check_members(n, v, ptr, depth, sink);
}

void Evaluator::check_members(const Node& n, const json& v, const std::string& ptr, int depth,
                              Sink& sink) {
  for (auto it = v.begin(); it != v.end() && !sink.done(); ++it) {
    const std::string member_ptr = child_pointer(ptr, it.key());
    const bool known = for_each_member_schema(n, it.key(), [&](const Node& schema) {
      descend(schema, it.value(), member_ptr, depth, sink);
    });
    if (known || !n.additional_properties) continue;
    if (is_false_schema(n.additional_properties)) {
      report_unknown(n, it.key(), member_ptr, sink);
    } else {
      descend(*n.additional_properties, it.value(), member_ptr, depth, sink);
    }
  }
}

// "is not a known field here; known fields: a, b, c — did you mean \"b\"?"
void Evaluator::report_unknown(const Node& n, const std::string& key, const std::string& ptr,
                               Sink& sink) {
  std::vector<std::string> known;
  for (const auto& entry : n.properties) known.push_back(entry.first);
  std::vector<std::string> patterns;
  for (const auto& entry : n.pattern_properties) patterns.push_back(quote(entry.pattern.source));

  std::string message;
  if (known.empty() && patterns.empty()) {
    message = "is not allowed here: this object takes no fields";
  } else {
    message = "is not a known field here";
    if (!known.empty()) message += "; known fields: " + join_listed(known);
    if (!patterns.empty()) {
      message +=
          std::string(known.empty() ? "; field names must match " : "; other names must match ") +
          join_or(patterns);
    }
  }
  sink.add(ptr, message + did_you_mean(key, known));
}

void Evaluator::check_property_names(const Node& n, const json& v, const std::string& ptr,
                                     int depth, Sink& sink) {
  for (auto it = v.begin(); it != v.end() && !sink.done(); ++it) {
    const std::string member_ptr = child_pointer(ptr, it.key());
    Sink name_sink(sink.first_only());
    descend(*n.property_names, json(it.key()), member_ptr, depth, name_sink);
    for (const Issue& issue : name_sink.issues()) {
      sink.add(member_ptr, "is not a valid field name: it " + issue.message);
    }
  }
}

void Evaluator::check_combinators(const Node& n, const json& v, const std::string& ptr, int depth,
                                  Sink& sink) {
  for (const Node* schema : n.all_of) {
    if (sink.done()) return;
    check(*schema, v, ptr, depth, sink);
  }
  if (!n.any_of.empty() && !sink.done()) check_any_of(n, v, ptr, depth, sink);
  if (!n.one_of.empty() && !sink.done()) check_one_of(n, v, ptr, depth, sink);
  if (n.not_schema && !sink.done()) check_not(n, v, ptr, depth, sink);
  if (n.if_schema && !sink.done()) {
    // then/else errors are reported as they are: they are about this value.
    const Node* branch = matches(*n.if_schema, v, ptr, depth) ? n.then_schema : n.else_schema;
    if (branch) check(*branch, v, ptr, depth, sink);
  }
}

void Evaluator::check_any_of(const Node& n, const json& v, const std::string& ptr, int depth,
                             Sink& sink) {
  std::vector<std::vector<Issue>> failures;
  for (const Node* branch : n.any_of) {
    Sink branch_sink(sink.first_only());
    check(*branch, v, ptr, depth, branch_sink);
    if (branch_sink.empty()) return;
    failures.push_back(std::move(branch_sink.issues()));
  }
  report_closest(failures, v, ptr, sink);
}

void Evaluator::check_one_of(const Node& n, const json& v, const std::string& ptr, int depth,
                             Sink& sink) {
  std::vector<std::vector<Issue>> failures;
  std::vector<const Node*> matched;
  for (const Node* branch : n.one_of) {
    Sink branch_sink(sink.first_only());
    check(*branch, v, ptr, depth, branch_sink);
    if (branch_sink.empty()) {
      matched.push_back(branch);
    } else {
      failures.push_back(std::move(branch_sink.issues()));
    }
  }
  if (matched.empty()) {
    report_closest(failures, v, ptr, sink);
    return;
  }
  if (matched.size() == 1) return;
  report_ambiguous(matched, ptr, sink);
}

void Evaluator::check_not(const Node& n, const json& v, const std::string& ptr, int depth,
                          Sink& sink) {
  if (matches(*n.not_schema, v, ptr, depth)) report_excluded(*n.not_schema, ptr, sink);
}

// Whether a branch failed on the kind or identity of the value itself or of
// a direct member (typically a discriminator such as "type": "plate"),
// which means the user most likely did not intend that branch.
bool rules_out(const std::vector<Issue>& issues, const std::string& ptr) {
  return std::any_of(issues.begin(), issues.end(), [&](const Issue& issue) {
    if (issue.kind == IssueKind::kOther) return false;
    if (issue.pointer == ptr) return true;
    const std::string prefix = ptr + "/";
    return issue.pointer.compare(0, prefix.size(), prefix) == 0 &&
           issue.pointer.find('/', prefix.size()) == std::string::npos;
  });
}

// When every branch failed only on the kind or identity of the value itself,
// says so in one message: "must be a number or \"auto\" (got \"x\")".
std::optional<Issue> merge_mismatches(const std::vector<std::vector<Issue>>& failures,
                                      const json& v, const std::string& ptr) {
  std::vector<std::string> expected, candidates;
  bool all_types = true;
  for (const auto& issues : failures) {
    if (issues.size() != 1 || issues[0].pointer != ptr || issues[0].kind == IssueKind::kOther) {
      return std::nullopt;
    }
    all_types = all_types && issues[0].kind == IssueKind::kType;
    for (const auto& phrase : issues[0].expected) {
      if (std::find(expected.begin(), expected.end(), phrase) == expected.end()) {
        expected.push_back(phrase);
      }
    }
    candidates.insert(candidates.end(), issues[0].candidates.begin(), issues[0].candidates.end());
  }
  std::string message;
  if (all_types) {
    message = type_message(expected, v);
  } else {
    message = "must be " + join_or(expected) + " (got " + describe_value(v) + ")";
    if (v.is_string()) message += did_you_mean(v.get_ref<const std::string&>(), candidates);
  }
  const IssueKind kind = all_types ? IssueKind::kType : IssueKind::kValue;
  return Issue{ptr, std::move(message), kind, std::move(expected), std::move(candidates)};
}

// No branch matched: report the branch that came closest. A branch ruled out
// by a wrong kind of value or discriminator ranks after the others; then
// fewer errors win, ties go to the first.
void Evaluator::report_closest(std::vector<std::vector<Issue>>& failures, const json& v,
                               const std::string& ptr, Sink& sink) {
  if (auto merged = merge_mismatches(failures, v, ptr)) {
    sink.add(std::move(*merged));
    return;
  }
  const auto rank = [&](const std::vector<Issue>& issues) {
    return std::make_pair(rules_out(issues, ptr), issues.size());
  };
  std::size_t best = 0;
  for (std::size_t i = 1; i < failures.size(); ++i) {
    if (rank(failures[i]) < rank(failures[best])) best = i;
  }
  sink.append(failures[best]);
}

// ---------------------------------------------------------------- defaults

class Filler {
 public:
  explicit Filler(long max_steps) : evaluator_(max_steps), max_steps_(max_steps) {}
  void fill(const Node& node, json& v, int depth);

 private:
  void fill_object(const Node& n, json& v, int depth);
  void fill_array(const Node& n, json& v, int depth);
  void fill_combinators(const Node& n, json& v, int depth);

  Evaluator evaluator_;  // answers if/anyOf/oneOf questions
  const long max_steps_;
  int frames_ = 0;
  long steps_ = 0;
};

void Filler::fill(const Node& node, json& v, int depth) {
  const Node& target = *resolve(&node);
  if (target.boolean || depth > kMaxInstanceDepth || ++steps_ > max_steps_) return;
  const FrameGuard frame(frames_);
  if (frame.too_deep()) return;
  if (v.is_object()) fill_object(target, v, depth);
  if (v.is_array()) fill_array(target, v, depth);
  fill_combinators(target, v, depth);
}

void Filler::fill_object(const Node& n, json& v, int depth) {
  for (const auto& [name, schema] : n.properties) {
    if (v.contains(name)) continue;
    if (const json* value = find_default(schema)) v[name] = *value;
  }
  for (auto it = v.begin(); it != v.end(); ++it) {
    json& value = it.value();
    const bool known = for_each_member_schema(
        n, it.key(), [&](const Node& schema) { fill(schema, value, depth + 1); });
    if (!known && n.additional_properties) fill(*n.additional_properties, value, depth + 1);
  }
}

void Filler::fill_array(const Node& n, json& v, int depth) {
  for (std::size_t i = 0; i < v.size(); ++i) {
    const Node* schema = n.items;
    if (n.tuple) schema = i < n.tuple->size() ? (*n.tuple)[i] : n.additional_items;
    if (schema) fill(*schema, v[i], depth + 1);
  }
}

// Branches are chosen on the value as filled so far, so a defaulted
// discriminator selects its branch.
void Filler::fill_combinators(const Node& n, json& v, int depth) {
  for (const Node* schema : n.all_of) fill(*schema, v, depth);
  for (const auto* branches : {&n.any_of, &n.one_of}) {
    for (const Node* branch : *branches) {
      if (evaluator_.matches(*branch, v, "", depth)) {
        fill(*branch, v, depth);
        break;
      }
    }
  }
  if (n.if_schema) {
    const Node* branch =
        evaluator_.matches(*n.if_schema, v, "", depth) ? n.then_schema : n.else_schema;
    if (branch) fill(*branch, v, depth);
  }
}

// Sorted by pointer (stable, so errors about one value keep their order),
// without repeats, at most `max_errors`.
std::vector<Error> finalize(std::vector<Issue>& issues, std::size_t max_errors) {
  std::stable_sort(issues.begin(), issues.end(),
                   [](const Issue& a, const Issue& b) { return a.pointer < b.pointer; });
  std::vector<Error> errors;
  std::set<std::pair<std::string, std::string>> seen;
  for (auto& issue : issues) {
    if (errors.size() >= max_errors) break;
    if (!seen.emplace(issue.pointer, issue.message).second) continue;
    errors.push_back(Error{std::move(issue.pointer), std::move(issue.message)});
  }
  return errors;
}

}  // namespace

struct Validator::Compiled {
  json schema;
  std::vector<std::unique_ptr<Node>> nodes;
  const Node* root = nullptr;
};

Validator::Validator(nlohmann::json schema) {
  auto compiled = std::make_shared<Compiled>();
  compiled->schema = std::move(schema);
  compiled->root = Compiler(compiled->schema, compiled->nodes).compile_root();
  compiled_ = std::move(compiled);
}

std::vector<Error> Validator::validate(const nlohmann::json& instance,
                                       std::size_t max_errors) const {
  Evaluator evaluator(step_budget(instance));
  Sink sink(false);
  evaluator.check(*compiled_->root, instance, "", 0, sink);
  if (evaluator.exhausted()) sink.add("", kTooComplexMessage);
  return finalize(sink.issues(), max_errors);
}

nlohmann::json Validator::apply_defaults(const nlohmann::json& instance) const {
  json result = deep_copy(instance);
  Filler(step_budget(result)).fill(*compiled_->root, result, 0);
  return result;
}

const nlohmann::json& Validator::schema() const {
  return compiled_->schema;
}

std::string escape_pointer_token(const std::string& token) {
  std::string out;
  out.reserve(token.size());
  for (char c : token) {
    if (c == '~') {
      out += "~0";
    } else if (c == '/') {
      out += "~1";
    } else {
      out += c;
    }
  }
  return out;
}

}  // namespace gearsph::jsonschema
