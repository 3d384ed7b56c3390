#pragma once
// A JSON Schema (draft-07 subset) validator over nlohmann::json, written for
// job files: its error messages are shown to users, so each one is a single
// plain sentence tied to the JSON pointer of the offending value.
//
// Supported keywords: type, enum, const, properties, required,
// additionalProperties, patternProperties, propertyNames, minProperties,
// maxProperties, items (single and tuple form), additionalItems, minItems,
// maxItems, uniqueItems, contains, minimum, maximum, exclusiveMinimum,
// exclusiveMaximum (numeric form), multipleOf, minLength, maxLength (in code
// points), pattern (std::regex ECMAScript, search semantics), allOf, anyOf,
// oneOf, not, if/then/else, $ref (local "#..." pointers only), definitions and
// boolean schemas. format, annotations and unknown keywords are ignored.
// As in draft-07, keywords next to a "$ref" are ignored when validating
// ("default" next to a "$ref" is still used by apply_defaults).
//
// Limits, so no instance can crash the caller: instances nested more than
// 200 levels deep get an "is nested too deeply" error, and strings longer than
// 1000 bytes are not matched against a pattern (std::regex recurses per
// character) but reported as too long to check.
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace gearsph::jsonschema {

struct Error {
  std::string pointer;  // RFC 6901 pointer into the instance; "" is the root
  std::string message;  // one English sentence about the value at `pointer`

  bool operator==(const Error&) const = default;
};

class Validator {
 public:
  // Throws std::invalid_argument on a malformed schema, an invalid pattern,
  // or a $ref that cannot be resolved inside this schema.
  explicit Validator(nlohmann::json schema);

  // Errors sorted by pointer (plain string order, stable), without
  // duplicates, at most `max_errors` of them. Empty means valid.
  std::vector<Error> validate(const nlohmann::json& instance, std::size_t max_errors = 50) const;

  // A copy of `instance` where absent properties whose schema has a
  // "default" are filled in, recursively. Present values are never changed,
  // and parts of the instance that do not fit the schema are left alone.
  nlohmann::json apply_defaults(const nlohmann::json& instance) const;

  const nlohmann::json& schema() const;

 private:
  struct Compiled;  // the schema compiled into a graph of nodes
  // Shared and immutable, so copies of a Validator are cheap and thread-safe.
  std::shared_ptr<const Compiled> compiled_;
};

// Escapes one reference token of a JSON pointer: "~" -> "~0", "/" -> "~1".
std::string escape_pointer_token(const std::string& token);

}  // namespace gearsph::jsonschema
