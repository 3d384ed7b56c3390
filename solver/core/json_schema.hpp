#pragma once
// JSON Schema (draft-07) checks for job files. Whether a value is valid is
// decided by valijson; this layer says why in words a user understands: each
// error is one plain sentence tied to the JSON pointer of the offending
// value, with "did you mean" for near misses of field names and enum values.
// It also fills in defaults, which valijson does not do.
//
// Beyond valijson:
// - Numbers with a zero fraction are integers, in schemas and instances
//   alike (draft-07: 3.0 is an integer, "minItems": 2.0 is a count).
// - Instances nested more than 200 levels deep get an "is nested too deeply"
//   error and are not checked further (valijson recurses per level).
// - When the schema matches strings against regular expressions ("pattern",
//   "patternProperties", "format"), strings and field names longer than
//   1000 bytes are reported as too long to check (std::regex recurses per
//   character).
// - A schema is refused at construction when a local "$ref" does not
//   resolve, when it refers to itself without descending into the value
//   (a loop of "$ref"s or of allOf/anyOf/oneOf/not/if), when a regular
//   expression does not compile, or when valijson refuses it. References to
//   other documents are not fetched.
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
  // Throws std::invalid_argument on a schema that cannot be used (above).
  explicit Validator(nlohmann::json schema);

  // Errors sorted by pointer (plain string order, stable), without
  // duplicates, at most `max_errors` of them. Empty means valid.
  std::vector<Error> validate(const nlohmann::json& instance, std::size_t max_errors = 50) const;

  // A copy of `instance` where absent properties whose schema has a
  // "default" are filled in, recursively ("default" next to a "$ref" wins
  // over the target's). Present values are never changed, and parts of the
  // instance that do not fit the schema are left alone. Branches of anyOf,
  // oneOf and if/then/else are chosen on the value as filled so far, so a
  // defaulted discriminator selects its branch.
  nlohmann::json apply_defaults(const nlohmann::json& instance) const;

  const nlohmann::json& schema() const;

 private:
  struct Compiled;
  // Shared and immutable but for a locked cache, so copies of a Validator
  // are cheap and thread-safe.
  std::shared_ptr<const Compiled> compiled_;
};

// Escapes one reference token of a JSON pointer: "~" -> "~0", "/" -> "~1".
std::string escape_pointer_token(const std::string& token);

}  // namespace gearsph::jsonschema
