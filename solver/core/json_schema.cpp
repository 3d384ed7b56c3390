// Every yes-or-no here comes from valijson: whether an instance is valid,
// whether a value matches a subschema, whether one keyword holds. This file
// only decides what to say about a value that valijson has refused (the
// Describer), which defaults to fill in (the Filler), and what valijson must
// not be given (schemas that refer to themselves in a loop, instances too
// deep or strings too long for its recursion).
// GCC 12 reports a false -Wmaybe-uninitialized inside libstdc++'s <regex>
// (std::function in its NFA states) when building with sanitizers, and a
// false -Wrestrict at -O3 in std::string::replace as valijson's JSON
// pointer code inlines it.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#pragma GCC diagnostic ignored "-Wrestrict"
#include "solver/core/json_schema.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <mutex>
#include <optional>
#include <regex>
#include <set>
#include <stdexcept>
#include <utility>

#include <valijson/adapters/nlohmann_json_adapter.hpp>
#include <valijson/schema.hpp>
#include <valijson/schema_parser.hpp>
#include <valijson/validator.hpp>
#pragma GCC diagnostic pop

#include "solver/core/schema_wording.hpp"

namespace gearsph::jsonschema {
namespace {

using json = nlohmann::json;
using namespace wording;

// Instances nested deeper than this are reported instead of checked.
constexpr int kMaxInstanceDepth = 200;
// libstdc++'s regex executor recurses once per character: longer subjects
// could overflow the stack, so they are not matched.
constexpr std::size_t kMaxRegexSubject = 1000;
// Errors kept while describing, before sorting and truncation.
constexpr std::size_t kErrorCap = 10'000;

// ---------------------------------------------------------------- pointers

std::string child_pointer(const std::string& pointer, const std::string& key) {
  return pointer + "/" + escape_pointer_token(key);
}

std::string child_pointer(const std::string& pointer, std::size_t index) {
  return pointer + "/" + std::to_string(index);
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

// The value at `pointer` (escaped tokens) in `root`; nullptr when there is
// none, with the token that was not found in `missing`.
const json* find_node(const json& root, const std::string& pointer, std::string* missing) {
  const json* node = &root;
  std::size_t start = 1;
  while (start <= pointer.size()) {
    const std::size_t slash = std::min(pointer.find('/', start), pointer.size());
    const std::string raw = pointer.substr(start, slash - start);
    const std::optional<std::string> token = unescape_token(raw);
    const std::optional<std::size_t> index = token ? parse_index(*token) : std::nullopt;
    if (token && node->is_object() && node->contains(*token)) {
      node = &(*node)[*token];
    } else if (index && node->is_array() && *index < node->size()) {
      node = &(*node)[*index];
    } else {
      if (missing) *missing = token.value_or(raw);
      return nullptr;
    }
    start = slash + 1;
  }
  return node;
}

// ----------------------------------------------------------------- numbers

// A copy where numbers with a zero fraction are integers: draft-07 counts
// 3.0 as an integer, valijson does not. Callers bound the depth.
json with_integral_numbers(const json& v) {
  if (v.is_number_float()) {
    const double x = v.get<double>();
    constexpr double kInt64Range = 9.2e18;
    if (std::isfinite(x) && std::floor(x) == x && std::fabs(x) < kInt64Range) {
      return static_cast<std::int64_t>(x);
    }
    return v;
  }
  if (v.is_array()) {
    json out = json::array();
    for (const auto& item : v) out.push_back(with_integral_numbers(item));
    return out;
  }
  if (v.is_object()) {
    json out = json::object();
    for (auto it = v.begin(); it != v.end(); ++it) out[it.key()] = with_integral_numbers(*it);
    return out;
  }
  return v;
}

// json's own copy recurses once per nesting level: arbitrarily deep
// instances are copied here without recursion.
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

// ------------------------------------------------------------------ issues

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

class Issues {
 public:
  void add(Issue issue) {
    if (!full()) items_.push_back(std::move(issue));
  }
  void add(const std::string& pointer, std::string message) {
    add(Issue{pointer, std::move(message), IssueKind::kOther, {}, {}});
  }
  bool full() const { return items_.size() >= kErrorCap; }
  std::size_t size() const { return items_.size(); }
  std::vector<Issue>& items() { return items_; }

 private:
  std::vector<Issue> items_;
};

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

// What keeps valijson from checking `instance` safely: values nested too
// deeply, and (when the schema matches strings against regular expressions)
// strings too long to match. Iterative, whatever the depth.
void find_unsafe_values(const json& instance, bool matches_strings, Issues& out) {
  struct Todo {
    const json* value;
    int depth;
    std::string pointer;
  };
  const std::string too_long = "too long to check against the schema's patterns (more than " +
                               std::to_string(kMaxRegexSubject) + " bytes)";
  std::vector<Todo> todo{{&instance, 0, ""}};
  while (!todo.empty() && !out.full()) {
    Todo next = std::move(todo.back());
    todo.pop_back();
    const json& v = *next.value;
    if (next.depth > kMaxInstanceDepth) {
      out.add(next.pointer,
              "is nested too deeply (more than " + std::to_string(kMaxInstanceDepth) + " levels)");
    } else if (v.is_string() && matches_strings &&
               v.get_ref<const std::string&>().size() > kMaxRegexSubject) {
      out.add(next.pointer, "is " + too_long);
    } else if (v.is_array()) {
      for (std::size_t i = v.size(); i-- > 0;) {
        todo.push_back({&v[i], next.depth + 1, child_pointer(next.pointer, i)});
      }
    } else if (v.is_object()) {
      for (auto it = v.begin(); it != v.end(); ++it) {
        const std::string pointer = child_pointer(next.pointer, it.key());
        if (matches_strings && it.key().size() > kMaxRegexSubject) {
          out.add(pointer, "has a field name " + too_long);
        }
        todo.push_back({&it.value(), next.depth + 1, pointer});
      }
    }
  }
}

// ----------------------------------------------------------------- schemas

[[noreturn]] void fail(const std::string& location, const std::string& what) {
  throw std::invalid_argument("invalid JSON schema at #" + location + ": " + what);
}

std::unique_ptr<valijson::Schema> parse_with_valijson(const json& document) {
  auto schema = std::make_unique<valijson::Schema>();
  valijson::SchemaParser parser(valijson::SchemaParser::kDraft7);
  const valijson::adapters::NlohmannJsonAdapter adapter(document);
  parser.populateSchema(adapter, *schema);
  return schema;
}

bool valijson_accepts(const valijson::Subschema& schema, const json& value) {
  valijson::Validator validator;  // holds a regex cache: one per call keeps this thread-safe
  const valijson::adapters::NlohmannJsonAdapter adapter(value);
  return validator.validate(schema, adapter, nullptr);
}

// The location (a JSON pointer into the schema) that a local "$ref" names;
// nullopt for a reference to another document. Throws when it names
// nothing.
std::optional<std::string> local_ref_target(const json& root, const std::string& location,
                                            const json& ref) {
  if (!ref.is_string()) fail(location, "\"$ref\" must be a string");
  const auto& text = ref.get_ref<const std::string&>();
  if (text.empty() || text[0] != '#') return std::nullopt;
  const auto cannot = [&](const std::string& why) {
    fail(location, "cannot resolve \"$ref\": " + quote(text) + " (" + why + ")");
  };
  const std::optional<std::string> fragment = percent_decode(text.substr(1));
  if (!fragment) cannot("bad percent-encoding");
  if (fragment->empty()) return "";
  if ((*fragment)[0] != '/') cannot("only JSON pointer fragments are supported");
  std::string missing;
  if (!find_node(root, *fragment, &missing)) cannot("nothing at " + quote(missing));
  return *fragment;
}

// Walks every subschema once before valijson sees the schema, refusing what
// valijson would loop or crash on, and noting whether it matches regular
// expressions.
class SchemaCheck {
 public:
  explicit SchemaCheck(const json& root) : root_(root) {}

  // Throws std::invalid_argument on the first problem.
  void run() {
    visit("");
    for (const auto& [location, next] : in_place_) check_no_loop_from(location);
  }
  bool matches_strings() const { return matches_strings_; }

 private:
  void visit(const std::string& location);
  void visit_keywords(const std::string& location, const json& s);
  void visit_in_place(const std::string& from, const std::string& to) {
    in_place_[from].push_back(to);
    visit(to);
  }
  void compile_pattern(const std::string& location, const json& source) {
    if (!source.is_string()) fail(location, "a pattern must be a string");
    try {
      std::regex(source.get<std::string>(), std::regex::ECMAScript);
    } catch (const std::regex_error& e) {
      fail(location,
           "invalid regular expression " + quote(source.get<std::string>()) + ": " + e.what());
    }
    matches_strings_ = true;
  }
  void check_no_loop_from(const std::string& location);

  const json& root_;
  std::set<std::string> visited_;
  // Subschemas applied to the same value: "$ref", allOf, anyOf, oneOf, not,
  // if/then/else, schema dependencies. A loop among them never ends.
  std::map<std::string, std::vector<std::string>> in_place_;
  std::set<std::string> loop_free_;
  bool matches_strings_ = false;
};

void SchemaCheck::visit(const std::string& location) {
  if (!visited_.insert(location).second) return;
  const json& s = *find_node(root_, location, nullptr);
  if (s.is_boolean()) return;
  if (!s.is_object()) fail(location, "a schema must be an object or a boolean, not " + kind_of(s));
  if (const auto it = s.find("definitions"); it != s.end()) {
    if (!it->is_object()) fail(location, "\"definitions\" must be an object");
    for (auto d = it->begin(); d != it->end(); ++d) {
      visit(child_pointer(location + "/definitions", d.key()));
    }
  }
  if (const auto ref = s.find("$ref"); ref != s.end()) {
    // draft-07: keywords next to "$ref" are ignored.
    if (const auto target = local_ref_target(root_, location, *ref)) {
      visit_in_place(location, *target);
    }
    return;
  }
  visit_keywords(location, s);
}

void SchemaCheck::visit_keywords(const std::string& location, const json& s) {
  for (const char* key : {"additionalItems", "additionalProperties", "contains", "propertyNames"}) {
    if (s.contains(key)) visit(location + "/" + key);
  }
  for (const char* key : {"not", "if", "then", "else"}) {
    if (s.contains(key)) visit_in_place(location, location + "/" + key);
  }
  for (const char* key : {"allOf", "anyOf", "oneOf"}) {
    const auto it = s.find(key);
    if (it == s.end()) continue;
    if (!it->is_array() || it->empty()) {
      fail(location, quote(key) + " must be a non-empty array of schemas");
    }
    for (std::size_t i = 0; i < it->size(); ++i) {
      visit_in_place(location, child_pointer(location + "/" + key, i));
    }
  }
  for (const char* key : {"properties", "patternProperties", "dependencies"}) {
    const auto it = s.find(key);
    if (it == s.end()) continue;
    if (!it->is_object()) fail(location, quote(key) + " must be an object");
    const std::string base = location + "/" + key;
    for (auto member = it->begin(); member != it->end(); ++member) {
      const std::string child = child_pointer(base, member.key());
      if (std::string(key) == "patternProperties") compile_pattern(child, member.key());
      if (std::string(key) != "dependencies") {
        visit(child);
      } else if (!member->is_array()) {  // an array lists required names
        visit_in_place(location, child);
      }
    }
  }
  if (const auto items = s.find("items"); items != s.end()) {
    if (!items->is_array()) {
      visit(location + "/items");
    } else {
      for (std::size_t i = 0; i < items->size(); ++i) visit(child_pointer(location + "/items", i));
    }
  }
  for (const char* key :
       {"minimum", "maximum", "exclusiveMinimum", "exclusiveMaximum", "multipleOf"}) {
    const auto it = s.find(key);
    if (it != s.end() && !it->is_number()) fail(location, quote(key) + " must be a number");
  }
  if (const auto divisor = s.find("multipleOf");
      divisor != s.end() && divisor->get<double>() <= 0) {
    fail(location, "\"multipleOf\" must be greater than 0");  // valijson would divide by it
  }
  if (const auto pattern = s.find("pattern"); pattern != s.end()) {
    compile_pattern(location, *pattern);
  }
  if (s.contains("format")) matches_strings_ = true;  // valijson checks dates with regexes
}

// Depth-first over the in-place edges: a path back to a location still on
// the stack is a loop.
void SchemaCheck::check_no_loop_from(const std::string& start) {
  std::vector<std::string> stack;
  std::set<std::string> on_stack;
  const auto walk = [&](const auto& self, const std::string& location) -> void {
    if (loop_free_.count(location)) return;
    if (on_stack.count(location)) {
      fail(location,
           "it refers to itself without descending into the value (a loop through $ref, allOf, "
           "anyOf, oneOf, not or if)");
    }
    on_stack.insert(location);
    if (const auto it = in_place_.find(location); it != in_place_.end()) {
      for (const std::string& next : it->second) self(self, next);
    }
    on_stack.erase(location);
    loop_free_.insert(location);
  };
  walk(walk, start);
}

// The schema as given, valijson's parse of it, and valijson's parses of the
// subschemas that the Describer and Filler ask about.
class CompiledSchema {
 public:
  explicit CompiledSchema(json schema) : schema_(std::move(schema)) {
    SchemaCheck check(schema_);
    check.run();
    matches_strings_ = check.matches_strings();
    normalised_ = with_integral_numbers(schema_);
    try {
      root_ = parse_with_valijson(normalised_);
    } catch (const std::exception& e) {  // valijson throws std::runtime_error
      throw std::invalid_argument(std::string("invalid JSON schema: ") + e.what());
    }
  }

  const json& schema() const { return schema_; }
  bool matches_strings() const { return matches_strings_; }
  const json& node(const std::string& location) const {
    return *find_node(schema_, location, nullptr);
  }

  // The end of the chain of local $refs that starts at `location`; nullopt
  // when the chain leaves this document. Chains end (SchemaCheck).
  std::optional<std::string> follow_refs(std::string location) const {
    while (true) {
      const json& s = node(location);
      const auto ref = s.is_object() ? s.find("$ref") : s.end();
      if (!s.is_object() || ref == s.end()) return location;
      const std::optional<std::string> target = local_ref_target(schema_, location, *ref);
      if (!target) return std::nullopt;
      location = *target;
    }
  }

  // Whether `value` matches the subschema at `location`; callers bound the
  // depth of `value` (find_unsafe_values).
  bool matches(const std::string& location, const json& value) const {
    return valijson_accepts(parsed(location, ""), with_integral_numbers(value));
  }
  // Whether one keyword of the subschema at `location` holds for `value`;
  // only for keywords without subschemas.
  bool holds(const std::string& location, const std::string& keyword, const json& value) const {
    return valijson_accepts(parsed(location, keyword), with_integral_numbers(value));
  }

 private:
  // valijson resolves a document's own "$ref"s against its root, so a
  // subschema is parsed as the whole schema with a "$ref" to it at the top
  // (draft-07 ignores what stands beside a "$ref"). A keyword on its own has
  // no references and is parsed alone.
  // The location is followed through its "$ref"s first: a "$ref" at the
  // top that led to another "$ref" back to the top would never end.
  const valijson::Subschema& parsed(const std::string& location, const std::string& keyword) const {
    const std::string target =
        keyword.empty() ? follow_refs(location).value_or(location) : location;
    if (target.empty() && keyword.empty()) return *root_;
    const std::string key = keyword.empty() ? target : target + " " + keyword;
    const std::lock_guard<std::mutex> lock(mutex_);
    auto& slot = parsed_[key];
    if (!slot) {
      json document;
      if (keyword.empty()) {
        document = normalised_;
        std::string ref = "#";
        for (char c : target) ref += c == '%' ? std::string("%25") : std::string(1, c);
        document["$ref"] = ref;
      } else {
        document = {{keyword, *find_node(normalised_, target + "/" + keyword, nullptr)}};
      }
      slot = parse_with_valijson(document);
    }
    return *slot;
  }

  json schema_;
  json normalised_;  // numbers with a zero fraction as integers: what valijson parses
  bool matches_strings_ = false;
  std::unique_ptr<valijson::Schema> root_;
  mutable std::mutex mutex_;
  mutable std::map<std::string, std::unique_ptr<valijson::Schema>> parsed_;
};

// ------------------------------------------------------------------ wording

// In the order types are listed in messages.
struct TypeName {
  const char* name;    // as spelled in a schema
  const char* phrase;  // as said in a message
};
constexpr TypeName kTypeNames[] = {
    {"object", "an object"}, {"array", "an array"},     {"string", "a string"},
    {"number", "a number"},  {"integer", "an integer"}, {"boolean", "a boolean"},
    {"null", "null"},
};

std::vector<std::string> type_phrases(const json& type) {
  const auto names = type.is_array() ? type : json::array({type});
  const auto named = [&](const char* name) {
    return std::find(names.begin(), names.end(), name) != names.end();
  };
  std::vector<std::string> phrases;
  for (const auto& t : kTypeNames) {
    if (std::string(t.name) == "integer" && named("number")) continue;  // integers are numbers
    if (named(t.name)) phrases.emplace_back(t.phrase);
  }
  return phrases;
}

// "must be a number, not a string (\"abc\")"; for a fractional number where
// only integers are accepted: "must be an integer (got 3.5)".
std::string type_message(const std::vector<std::string>& expected, const json& v) {
  const std::string head = "must be " + join_or(expected);
  const bool integer_expected =
      std::find(expected.begin(), expected.end(), "an integer") != expected.end();
  if (v.is_number() && integer_expected) return head + " (got " + describe_value(v) + ")";
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
Issue value_issue(const std::string& pointer, const json& accepted, const json& v) {
  std::vector<std::string> expected = value_phrases(accepted);
  std::vector<std::string> candidates = string_values(accepted);
  std::string message;
  if (expected.empty()) {
    message = "is not allowed here: no value is accepted";  // "enum": []
  } else {
    message = expected.size() == 1 ? "must be " + expected.front()
                                   : "must be one of " + join_listed(expected);
    message += " (got " + describe_value(v) + ")";
    if (v.is_string()) message += did_you_mean(v.get_ref<const std::string&>(), candidates);
  }
  return Issue{pointer, std::move(message), IssueKind::kValue, std::move(expected),
               std::move(candidates)};
}

// A schema's title, else a short description, for naming oneOf branches.
std::optional<std::string> label_of(const json& s) {
  constexpr std::size_t kMaxLabel = 60;
  if (!s.is_object()) return std::nullopt;
  for (const char* key : {"title", "description"}) {
    const auto text = s.find(key);
    if (text != s.end() && text->is_string() &&
        text->get_ref<const std::string&>().size() <= kMaxLabel) {
      return text->get<std::string>();
    }
  }
  return std::nullopt;
}

// A short phrase for what a schema accepts ("a string", "3", "one of 1, 2"),
// used by "not" and "contains"; nullopt when there is no brief way to say it.
std::optional<std::string> accepted_phrase(const json& s) {
  if (!s.is_object()) return std::nullopt;
  if (const auto c = s.find("const"); c != s.end()) return expected_value(*c);
  if (const auto e = s.find("enum"); e != s.end() && e->is_array()) {
    if (e->size() == 1) return expected_value(e->at(0));
    return "one of " + join_listed(value_phrases(*e));
  }
  if (const auto t = s.find("type"); t != s.end()) return join_or(type_phrases(*t));
  return std::nullopt;
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
void report_closest(std::vector<std::vector<Issue>>& failures, const json& v,
                    const std::string& ptr, Issues& out) {
  if (auto merged = merge_mismatches(failures, v, ptr)) {
    out.add(std::move(*merged));
    return;
  }
  const auto rank = [&](const std::vector<Issue>& issues) {
    return std::make_pair(rules_out(issues, ptr), issues.size());
  };
  std::size_t best = 0;
  for (std::size_t i = 1; i < failures.size(); ++i) {
    if (rank(failures[i]) < rank(failures[best])) best = i;
  }
  for (auto& issue : failures[best]) out.add(std::move(issue));
}

// --------------------------------------------------------------- describer

// Says why a value fails a subschema, keyword by keyword, in the order a
// reader checks them: kind, value, bounds, members or items, combinations.
class Describer {
 public:
  explicit Describer(const CompiledSchema& schema) : schema_(schema) {}

  // `v` at `ptr` fails the subschema at `location` (valijson said so).
  void describe(const std::string& location, const json& v, const std::string& ptr,
                Issues& out) const;

 private:
  bool fails(const std::string& at, const json& s, const char* keyword, const json& v) const {
    return s.contains(keyword) && !schema_.holds(at, keyword, v);
  }
  // Describes `v` against the subschema at `location` unless it matches.
  void check(const std::string& location, const json& v, const std::string& ptr,
             Issues& out) const {
    if (!out.full() && !schema_.matches(location, v)) describe(location, v, ptr, out);
  }
  std::vector<Issue> branch_issues(const std::string& location, const json& v,
                                   const std::string& ptr) const {
    Issues issues;
    describe(location, v, ptr, issues);
    return std::move(issues.items());
  }

  void numbers(const std::string& at, const json& s, const json& v, const std::string& ptr,
               Issues& out) const;
  void strings(const std::string& at, const json& s, const json& v, const std::string& ptr,
               Issues& out) const;
  void arrays(const std::string& at, const json& s, const json& v, const std::string& ptr,
              Issues& out) const;
  void objects(const std::string& at, const json& s, const json& v, const std::string& ptr,
               Issues& out) const;
  void members(const std::string& at, const json& s, const json& v, const std::string& ptr,
               Issues& out) const;
  void combinations(const std::string& at, const json& s, const json& v, const std::string& ptr,
                    Issues& out) const;

  const CompiledSchema& schema_;
};

void Describer::describe(const std::string& location, const json& v, const std::string& ptr,
                         Issues& out) const {
  const std::optional<std::string> at = schema_.follow_refs(location);
  if (!at) {  // another document: valijson knows why, this layer does not
    out.add(ptr, "does not match the schema");
    return;
  }
  const json& s = schema_.node(*at);
  if (s.is_boolean()) {  // only `false` refuses
    out.add(ptr, "is not allowed here");
    return;
  }
  const std::size_t before = out.size();
  if (fails(*at, s, "type", v)) {
    // After a type mismatch the other keywords would only repeat it.
    std::vector<std::string> expected = type_phrases(s["type"]);
    std::string message = type_message(expected, v);
    out.add(Issue{ptr, std::move(message), IssueKind::kType, std::move(expected), {}});
    return;
  }
  if (fails(*at, s, "const", v)) out.add(value_issue(ptr, json::array({s["const"]}), v));
  if (fails(*at, s, "enum", v)) out.add(value_issue(ptr, s["enum"], v));
  if (v.is_number()) numbers(*at, s, v, ptr, out);
  if (v.is_string()) strings(*at, s, v, ptr, out);
  if (v.is_array()) arrays(*at, s, v, ptr, out);
  if (v.is_object()) objects(*at, s, v, ptr, out);
  combinations(*at, s, v, ptr, out);
  // A refusal this layer cannot put in words is still reported.
  if (out.size() == before) out.add(ptr, "does not match the schema");
}

void Describer::numbers(const std::string& at, const json& s, const json& v, const std::string& ptr,
                        Issues& out) const {
  const std::string got = " (got " + format_number(v) + ")";
  const std::pair<const char*, const char*> bounds[] = {
      {"minimum", "must be at least "},         {"exclusiveMinimum", "must be greater than "},
      {"maximum", "must be at most "},          {"exclusiveMaximum", "must be less than "},
      {"multipleOf", "must be a multiple of "},
  };
  for (const auto& [keyword, phrase] : bounds) {
    if (fails(at, s, keyword, v)) out.add(ptr, phrase + format_number(s[keyword]) + got);
  }
}

void Describer::strings(const std::string& at, const json& s, const json& v, const std::string& ptr,
                        Issues& out) const {
  const std::size_t length = count_code_points(v.get_ref<const std::string&>());
  if (fails(at, s, "minLength", v)) {
    const std::string least = plural(s["minLength"].get<std::size_t>(), "character");
    out.add(ptr, length == 0
                     ? "must not be empty (at least " + least + ")"
                     : "must be at least " + least + " long (got " + describe_value(v) + ")");
  }
  if (fails(at, s, "maxLength", v)) {
    out.add(ptr, "must be at most " + plural(s["maxLength"].get<std::size_t>(), "character") +
                     " long (got " + plural(length, "character") + ")");
  }
  if (fails(at, s, "pattern", v)) {
    out.add(ptr, "must match the pattern " + quote(s["pattern"].get<std::string>()) + " (got " +
                     describe_value(v) + ")");
  }
  if (fails(at, s, "format", v) && s["format"].is_string()) {
    out.add(ptr, "must be a valid " + s["format"].get<std::string>() + " (got " +
                     describe_value(v) + ")");
  }
}

void Describer::arrays(const std::string& at, const json& s, const json& v, const std::string& ptr,
                       Issues& out) const {
  const std::string count = " (got " + std::to_string(v.size()) + ")";
  if (fails(at, s, "minItems", v)) {
    const std::string least = plural(s["minItems"].get<std::size_t>(), "item");
    out.add(ptr, v.empty() ? "must not be empty (at least " + least + ")"
                           : "must have at least " + least + count);
  }
  if (fails(at, s, "maxItems", v)) {
    out.add(ptr, "must have at most " + plural(s["maxItems"].get<std::size_t>(), "item") + count);
  }
  if (fails(at, s, "uniqueItems", v)) {
    // Each item equal to an earlier one, named by the first of them; sorting
    // finds them in n log n.
    std::vector<std::size_t> order(v.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return v[a] < v[b]; });
    std::vector<std::pair<std::size_t, std::size_t>> repeats;  // (later, first)
    for (std::size_t k = 1, first = 0; k < order.size(); ++k) {
      if (v[order[k]] == v[order[first]]) {
        repeats.emplace_back(order[k], order[first]);
      } else {
        first = k;
      }
    }
    std::sort(repeats.begin(), repeats.end());
    for (const auto& [later, first] : repeats) {
      out.add(child_pointer(ptr, later),
              "repeats item " + std::to_string(first) + "; all items must be different");
    }
  }
  if (const auto items = s.find("items"); items != s.end() && !items->is_array()) {
    for (std::size_t i = 0; i < v.size(); ++i)
      check(at + "/items", v[i], child_pointer(ptr, i), out);
  } else if (items != s.end()) {
    const std::size_t fixed = std::min(v.size(), items->size());
    for (std::size_t i = 0; i < fixed; ++i) {
      check(child_pointer(at + "/items", i), v[i], child_pointer(ptr, i), out);
    }
    const auto additional = s.find("additionalItems");
    if (v.size() > fixed && additional != s.end() && *additional == false) {
      // Same wording as maxItems, so the two collapse into one error.
      out.add(ptr, "must have at most " + plural(fixed, "item") + count);
    } else if (additional != s.end()) {
      for (std::size_t i = fixed; i < v.size(); ++i) {
        check(at + "/additionalItems", v[i], child_pointer(ptr, i), out);
      }
    }
  }
  if (const auto contains = s.find("contains"); contains != s.end()) {
    const bool found = std::any_of(v.begin(), v.end(), [&](const json& item) {
      return schema_.matches(at + "/contains", item);
    });
    if (!found) {
      const std::optional<std::string> phrase = accepted_phrase(*contains);
      std::string message = phrase ? "must contain at least one item that is " + *phrase
                                   : "must contain at least one item of the required form";
      if (v.empty()) message += " (it is empty)";
      out.add(ptr, message);
    }
  }
}

void Describer::objects(const std::string& at, const json& s, const json& v, const std::string& ptr,
                        Issues& out) const {
  const std::string count = " (got " + std::to_string(v.size()) + ")";
  if (fails(at, s, "minProperties", v)) {
    out.add(ptr,
            "must have at least " + plural(s["minProperties"].get<std::size_t>(), "field") + count);
  }
  if (fails(at, s, "maxProperties", v)) {
    out.add(ptr,
            "must have at most " + plural(s["maxProperties"].get<std::size_t>(), "field") + count);
  }
  if (fails(at, s, "required", v)) {
    for (const auto& name : s["required"]) {
      if (!v.contains(name.get<std::string>())) {
        out.add(child_pointer(ptr, name.get<std::string>()), "is required");
      }
    }
  }
  if (s.contains("propertyNames")) {
    for (auto it = v.begin(); it != v.end(); ++it) {
      const std::string member = child_pointer(ptr, it.key());
      if (schema_.matches(at + "/propertyNames", json(it.key()))) continue;
      for (Issue& issue : branch_issues(at + "/propertyNames", json(it.key()), member)) {
        out.add(member, "is not a valid field name: it " + issue.message);
      }
    }
  }
  members(at, s, v, ptr, out);
  if (const auto dependencies = s.find("dependencies"); dependencies != s.end()) {
    for (auto dep = dependencies->begin(); dep != dependencies->end(); ++dep) {
      if (!v.contains(dep.key())) continue;
      if (!dep->is_array()) {
        check(child_pointer(at + "/dependencies", dep.key()), v, ptr, out);
        continue;
      }
      for (const auto& name : *dep) {
        if (!v.contains(name.get<std::string>())) {
          out.add(child_pointer(ptr, name.get<std::string>()),
                  "is required when " + quote(dep.key()) + " is given");
        }
      }
    }
  }
}

// Each member against the schemas that apply to it; an unknown member where
// "additionalProperties" is false is named with the known ones:
// "is not a known field here; known fields: a, b, c — did you mean \"b\"?"
void Describer::members(const std::string& at, const json& s, const json& v, const std::string& ptr,
                        Issues& out) const {
  static const json kNone = json::object();
  const auto& properties = s.contains("properties") ? s["properties"] : kNone;
  const auto& patterns = s.contains("patternProperties") ? s["patternProperties"] : kNone;
  const auto additional = s.find("additionalProperties");
  for (auto it = v.begin(); it != v.end() && !out.full(); ++it) {
    const std::string member = child_pointer(ptr, it.key());
    bool known = properties.contains(it.key());
    if (known) check(child_pointer(at + "/properties", it.key()), *it, member, out);
    for (auto p = patterns.begin(); p != patterns.end(); ++p) {
      if (!std::regex_search(it.key(), std::regex(p.key(), std::regex::ECMAScript))) continue;
      known = true;
      check(child_pointer(at + "/patternProperties", p.key()), *it, member, out);
    }
    if (known || additional == s.end()) continue;
    if (*additional != false) {
      check(at + "/additionalProperties", *it, member, out);
      continue;
    }
    std::vector<std::string> names, sources;
    for (auto p = properties.begin(); p != properties.end(); ++p) names.push_back(p.key());
    for (auto p = patterns.begin(); p != patterns.end(); ++p) sources.push_back(quote(p.key()));
    std::string message = "is not allowed here: this object takes no fields";
    if (!names.empty() || !sources.empty()) {
      message = "is not a known field here";
      if (!names.empty()) message += "; known fields: " + join_listed(names);
      if (!sources.empty()) {
        message +=
            std::string(names.empty() ? "; field names must match " : "; other names must match ") +
            join_or(sources);
      }
    }
    out.add(member, message + did_you_mean(it.key(), names));
  }
}

void Describer::combinations(const std::string& at, const json& s, const json& v,
                             const std::string& ptr, Issues& out) const {
  if (const auto all = s.find("allOf"); all != s.end()) {
    for (std::size_t i = 0; i < all->size(); ++i)
      check(child_pointer(at + "/allOf", i), v, ptr, out);
  }
  for (const char* key : {"anyOf", "oneOf"}) {
    const auto branches = s.find(key);
    if (branches == s.end() || out.full()) continue;
    std::vector<std::vector<Issue>> failures;
    std::vector<std::size_t> matched;
    for (std::size_t i = 0; i < branches->size(); ++i) {
      const std::string branch = child_pointer(at + "/" + key, i);
      if (schema_.matches(branch, v)) {
        matched.push_back(i);
      } else {
        failures.push_back(branch_issues(branch, v, ptr));
      }
    }
    if (matched.empty()) {
      report_closest(failures, v, ptr, out);
    } else if (matched.size() > 1 && std::string(key) == "oneOf") {
      std::vector<std::string> labels;
      for (std::size_t i : matched) {
        const auto target = schema_.follow_refs(child_pointer(at + "/oneOf", i));
        const auto label = label_of((*branches)[i]);
        const auto target_label = target ? label_of(schema_.node(*target)) : std::nullopt;
        if (label || target_label) labels.push_back(quote(label ? *label : *target_label));
      }
      std::string message = "matches more than one of the allowed forms";
      if (labels.size() == matched.size()) message += " (" + join_or(labels) + ")";
      out.add(ptr, message);
    }
  }
  if (const auto excluded = s.find("not"); excluded != s.end() && schema_.matches(at + "/not", v)) {
    const auto target = schema_.follow_refs(at + "/not");
    const json& e = target ? schema_.node(*target) : *excluded;
    if (const std::optional<std::string> phrase = accepted_phrase(e)) {
      out.add(ptr, "must not be " + *phrase);
    } else if (e.is_object() && e.contains("required") && !e["required"].empty()) {
      std::vector<std::string> names;  // the idiom for forbidden fields
      for (const auto& name : e["required"]) names.push_back(quote(name.get<std::string>()));
      out.add(ptr, std::string(names.size() == 1 ? "must not have the field "
                                                 : "must not have all of the fields ") +
                       join_words(names, "and"));
    } else if (const auto label = label_of(e)) {
      out.add(ptr, "must not match " + quote(*label));
    } else {
      out.add(ptr, "must not match the excluded form");
    }
  }
  if (s.contains("if")) {
    // then/else errors are reported as they are: they are about this value.
    const char* branch = schema_.matches(at + "/if", v) ? "then" : "else";
    if (s.contains(branch)) check(at + "/" + branch, v, ptr, out);
  }
}

// ---------------------------------------------------------------- defaults

// The "default" of a property's schema, looking through $refs: the first
// one on the way wins, so a default next to a "$ref" overrides the target's.
const json* find_default(const CompiledSchema& schema, std::string location) {
  while (true) {
    const json& s = schema.node(location);
    if (!s.is_object()) return nullptr;
    if (const auto d = s.find("default"); d != s.end()) return &*d;
    const auto ref = s.find("$ref");
    if (ref == s.end()) return nullptr;
    const auto target = local_ref_target(schema.schema(), location, *ref);
    if (!target) return nullptr;
    location = *target;
  }
}

class Filler {
 public:
  explicit Filler(const CompiledSchema& schema) : schema_(schema) {}
  void fill(const std::string& location, json& v, int depth) const;

 private:
  // Branch questions are asked about the value as filled so far.
  bool matches(const std::string& location, const json& v) const {
    return schema_.matches(location, v);
  }
  void fill_object(const std::string& at, const json& s, json& v, int depth) const;
  void fill_array(const std::string& at, const json& s, json& v, int depth) const;
  void fill_combinations(const std::string& at, const json& s, json& v, int depth) const;

  const CompiledSchema& schema_;
};

void Filler::fill(const std::string& location, json& v, int depth) const {
  const std::optional<std::string> at = schema_.follow_refs(location);
  if (!at || depth > kMaxInstanceDepth) return;
  const json& s = schema_.node(*at);
  if (!s.is_object()) return;
  if (v.is_object()) fill_object(*at, s, v, depth);
  if (v.is_array()) fill_array(*at, s, v, depth);
  fill_combinations(*at, s, v, depth);
}

void Filler::fill_object(const std::string& at, const json& s, json& v, int depth) const {
  const auto properties = s.find("properties");
  if (properties != s.end()) {
    for (auto p = properties->begin(); p != properties->end(); ++p) {
      if (v.contains(p.key())) continue;
      const json* value = find_default(schema_, child_pointer(at + "/properties", p.key()));
      if (value) v[p.key()] = *value;
    }
  }
  const auto patterns = s.find("patternProperties");
  const auto additional = s.find("additionalProperties");
  for (auto it = v.begin(); it != v.end(); ++it) {
    bool known = false;
    if (properties != s.end() && properties->contains(it.key())) {
      known = true;
      fill(child_pointer(at + "/properties", it.key()), *it, depth + 1);
    }
    if (patterns != s.end()) {
      for (auto p = patterns->begin(); p != patterns->end(); ++p) {
        if (!std::regex_search(it.key(), std::regex(p.key(), std::regex::ECMAScript))) continue;
        known = true;
        fill(child_pointer(at + "/patternProperties", p.key()), *it, depth + 1);
      }
    }
    if (!known && additional != s.end()) fill(at + "/additionalProperties", *it, depth + 1);
  }
}

void Filler::fill_array(const std::string& at, const json& s, json& v, int depth) const {
  const auto items = s.find("items");
  if (items == s.end()) return;
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (!items->is_array()) {
      fill(at + "/items", v[i], depth + 1);
    } else if (i < items->size()) {
      fill(child_pointer(at + "/items", i), v[i], depth + 1);
    } else if (s.contains("additionalItems")) {
      fill(at + "/additionalItems", v[i], depth + 1);
    }
  }
}

// allOf: every branch; anyOf and oneOf: the first branch that matches;
// if: then or else.
void Filler::fill_combinations(const std::string& at, const json& s, json& v, int depth) const {
  if (const auto all = s.find("allOf"); all != s.end()) {
    for (std::size_t i = 0; i < all->size(); ++i) fill(child_pointer(at + "/allOf", i), v, depth);
  }
  for (const char* key : {"anyOf", "oneOf"}) {
    const auto branches = s.find(key);
    if (branches == s.end()) continue;
    for (std::size_t i = 0; i < branches->size(); ++i) {
      const std::string branch = child_pointer(at + "/" + key, i);
      if (matches(branch, v)) {
        fill(branch, v, depth);
        break;
      }
    }
  }
  if (s.contains("if")) {
    const char* branch = matches(at + "/if", v) ? "then" : "else";
    if (s.contains(branch)) fill(at + "/" + branch, v, depth);
  }
}

}  // namespace

struct Validator::Compiled {
  explicit Compiled(json schema) : compiled(std::move(schema)) {}
  CompiledSchema compiled;
};

Validator::Validator(nlohmann::json schema)
    : compiled_(std::make_shared<const Compiled>(std::move(schema))) {}

std::vector<Error> Validator::validate(const nlohmann::json& instance,
                                       std::size_t max_errors) const {
  const CompiledSchema& schema = compiled_->compiled;
  Issues issues;
  find_unsafe_values(instance, schema.matches_strings(), issues);
  if (issues.size() > 0) return finalize(issues.items(), max_errors);
  try {
    if (schema.matches("", instance)) return {};
    Describer(schema).describe("", instance, "", issues);
  } catch (const std::exception& e) {  // valijson throws on what it cannot check
    issues.add("", std::string("could not be checked: ") + e.what());
  }
  return finalize(issues.items(), max_errors);
}

nlohmann::json Validator::apply_defaults(const nlohmann::json& instance) const {
  json result = deep_copy(instance);
  Issues unsafe;
  find_unsafe_values(instance, compiled_->compiled.matches_strings(), unsafe);
  if (unsafe.size() > 0) return result;  // validate() reports it
  try {
    Filler(compiled_->compiled).fill("", result, 0);
  } catch (const std::exception&) {  // valijson could not answer: validate() reports it
  }
  return result;
}

const nlohmann::json& Validator::schema() const {
  return compiled_->compiled.schema();
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
