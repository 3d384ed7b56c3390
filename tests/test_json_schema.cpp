#include "solver/core/json_schema.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <optional>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using gearsph::jsonschema::Error;
using gearsph::jsonschema::escape_pointer_token;
using gearsph::jsonschema::Validator;
using nlohmann::json;

std::vector<Error> errors_of(const json& schema, const json& instance) {
  return Validator(schema).validate(instance);
}

bool is_valid(const json& schema, const json& instance) {
  return errors_of(schema, instance).empty();
}

std::string describe(const std::vector<Error>& errors) {
  std::string out;
  for (const auto& e : errors) out += "  [" + e.pointer + "] " + e.message + "\n";
  return out.empty() ? "  (no errors)\n" : out;
}

// Passes when some error at `pointer` contains every one of `phrases`.
::testing::AssertionResult has_error(const std::vector<Error>& errors, const std::string& pointer,
                                     const std::vector<std::string>& phrases) {
  for (const auto& e : errors) {
    if (e.pointer != pointer) continue;
    const bool all = std::all_of(phrases.begin(), phrases.end(), [&](const std::string& p) {
      return e.message.find(p) != std::string::npos;
    });
    if (all) return ::testing::AssertionSuccess();
  }
  auto failure = ::testing::AssertionFailure() << "no error at \"" << pointer << "\" containing";
  for (const auto& p : phrases) failure << " <" << p << ">";
  return failure << "; got:\n" << describe(errors);
}

// The only error, for tests that pin down one message.
Error single_error(const json& schema, const json& instance) {
  const auto errors = errors_of(schema, instance);
  EXPECT_EQ(errors.size(), 1u) << describe(errors);
  return errors.empty() ? Error{"<none>", ""} : errors.front();
}

bool contains(const std::string& haystack, const std::string& needle) {
  return haystack.find(needle) != std::string::npos;
}

// ------------------------------------------------------------------ basics

TEST(JsonSchemaPointer, EscapesTildeAndSlash) {
  EXPECT_EQ(escape_pointer_token("plain"), "plain");
  EXPECT_EQ(escape_pointer_token("a/b"), "a~1b");
  EXPECT_EQ(escape_pointer_token("a~b"), "a~0b");
  EXPECT_EQ(escape_pointer_token("~/"), "~0~1");
  EXPECT_EQ(escape_pointer_token(""), "");
}

TEST(JsonSchemaBasics, SchemaAccessorReturnsTheSchema) {
  const json schema = {{"type", "object"}, {"title", "Job"}};
  const Validator validator(schema);
  EXPECT_EQ(validator.schema(), schema);
}

TEST(JsonSchemaBasics, CopiesOutliveTheOriginal) {
  std::optional<Validator> original(std::in_place, json{{"minimum", 1}});
  const Validator copy = *original;
  original.reset();
  EXPECT_TRUE(copy.validate(2).empty());
  EXPECT_FALSE(copy.validate(0).empty());
}

TEST(JsonSchemaBasics, BooleanSchemas) {
  EXPECT_TRUE(is_valid(true, json::array({1, "x"})));
  EXPECT_TRUE(is_valid(json::object(), "anything"));
  const Error e = single_error(false, 1);
  EXPECT_EQ(e.pointer, "");
  EXPECT_TRUE(contains(e.message, "not allowed"));

  const json schema = {{"properties", {{"legacy", false}}}, {"items", false}};
  EXPECT_TRUE(has_error(errors_of(schema, {{"legacy", 1}}), "/legacy", {"not allowed"}));
  EXPECT_TRUE(has_error(errors_of({{"items", false}}, json::array({1})), "/0", {"not allowed"}));
  EXPECT_TRUE(is_valid({{"items", false}}, json::array()));
}

TEST(JsonSchemaBasics, IgnoresAnnotationsFormatAndUnknownKeywords) {
  const json schema = {{"$schema", "http://json-schema.org/draft-07/schema#"},
                       {"$id", "http://example.com/job.json"},
                       {"$comment", "x"},
                       {"title", "T"},
                       {"description", "D"},
                       {"examples", json::array({1})},
                       {"readOnly", true},
                       {"format", "email"},
                       {"x-gearsph-unit", "m"},
                       {"type", "string"}};
  EXPECT_TRUE(is_valid(schema, "not an email"));
  EXPECT_FALSE(is_valid(schema, 3));
}

// ------------------------------------------------------------------- type

TEST(JsonSchemaType, EachTypeAcceptsItsValues) {
  EXPECT_TRUE(is_valid({{"type", "null"}}, nullptr));
  EXPECT_TRUE(is_valid({{"type", "boolean"}}, false));
  EXPECT_TRUE(is_valid({{"type", "object"}}, json::object()));
  EXPECT_TRUE(is_valid({{"type", "array"}}, json::array()));
  EXPECT_TRUE(is_valid({{"type", "string"}}, ""));
  EXPECT_TRUE(is_valid({{"type", "number"}}, 1.5));
  EXPECT_TRUE(is_valid({{"type", "number"}}, 7));  // integers are numbers
  EXPECT_TRUE(is_valid({{"type", "integer"}}, 7));
  EXPECT_TRUE(is_valid({{"type", "integer"}}, 3.0));  // integral value
  EXPECT_TRUE(is_valid({{"type", "integer"}}, -4));
  EXPECT_TRUE(is_valid({{"type", "integer"}}, json::parse("18446744073709551615")));

  EXPECT_FALSE(is_valid({{"type", "integer"}}, 3.5));
  EXPECT_FALSE(is_valid({{"type", "string"}}, nullptr));
  EXPECT_FALSE(is_valid({{"type", "boolean"}}, 0));
  EXPECT_FALSE(is_valid({{"type", "object"}}, json::array()));
  EXPECT_FALSE(is_valid({{"type", "array"}}, json::object()));
  EXPECT_FALSE(is_valid({{"type", "null"}}, false));
}

TEST(JsonSchemaType, TypeArrays) {
  const json schema = {{"type", {"string", "null"}}};
  EXPECT_TRUE(is_valid(schema, "x"));
  EXPECT_TRUE(is_valid(schema, nullptr));
  const Error e = single_error(schema, 4);
  EXPECT_TRUE(contains(e.message, "a string or null")) << e.message;
  EXPECT_TRUE(contains(e.message, "not a number (4)")) << e.message;
}

TEST(JsonSchemaType, MessagesNameBothKindsAndShowShortValues) {
  Error e = single_error({{"type", "number"}}, "abc");
  EXPECT_EQ(e.message, "must be a number, not a string (\"abc\")");
  e = single_error({{"type", "string"}}, true);
  EXPECT_TRUE(contains(e.message, "must be a string, not a boolean (true)")) << e.message;
  e = single_error({{"type", "object"}}, json::array({1, 2}));
  EXPECT_TRUE(contains(e.message, "must be an object, not an array")) << e.message;
  e = single_error({{"type", "integer"}}, 3.5);
  EXPECT_TRUE(contains(e.message, "must be an integer")) << e.message;
  EXPECT_TRUE(contains(e.message, "3.5")) << e.message;
  e = single_error({{"type", "number"}}, nullptr);
  EXPECT_TRUE(contains(e.message, "not null")) << e.message;
}

TEST(JsonSchemaType, LongStringsAreAbbreviated) {
  const std::string long_text(500, 'x');
  const Error e = single_error({{"type", "number"}}, long_text);
  EXPECT_LT(e.message.size(), 120u) << e.message;
  EXPECT_TRUE(contains(e.message, "...")) << e.message;
}

TEST(JsonSchemaType, TypeMismatchSuppressesFollowUpNoise) {
  const json schema = {{"type", "string"}, {"enum", {"a", "b"}}, {"minLength", 2}};
  EXPECT_EQ(errors_of(schema, 5).size(), 1u);
}

// -------------------------------------------------------------- enum, const

TEST(JsonSchemaEnum, AcceptsListedValuesOnly) {
  const json schema = {{"enum", {"plate", "strip_wave", "spinning_disk", 3, nullptr}}};
  EXPECT_TRUE(is_valid(schema, "plate"));
  EXPECT_TRUE(is_valid(schema, 3));
  EXPECT_TRUE(is_valid(schema, 3.0));  // equal numbers are the same JSON value
  EXPECT_TRUE(is_valid(schema, nullptr));
  EXPECT_FALSE(is_valid(schema, "Plate "));
  EXPECT_FALSE(is_valid(schema, 4));
}

TEST(JsonSchemaEnum, MessageListsValuesAndSuggestsCloseSpelling) {
  const json schema = {{"enum", {"plate", "strip_wave", "spinning_disk"}}};
  Error e = single_error(schema, "plat");
  EXPECT_TRUE(contains(e.message, "must be one of \"plate\", \"strip_wave\", \"spinning_disk\""))
      << e.message;
  EXPECT_TRUE(contains(e.message, "(got \"plat\")")) << e.message;
  EXPECT_TRUE(contains(e.message, "did you mean \"plate\"?")) << e.message;

  e = single_error(schema, "spining_disk");
  EXPECT_TRUE(contains(e.message, "did you mean \"spinning_disk\"?")) << e.message;
  e = single_error(schema, "palte");  // swapped letters count as one edit
  EXPECT_TRUE(contains(e.message, "did you mean \"plate\"?")) << e.message;
  e = single_error(schema, "PLATE");  // case differences are forgiven
  EXPECT_TRUE(contains(e.message, "did you mean \"plate\"?")) << e.message;
  e = single_error(schema, "cylinder");
  EXPECT_FALSE(contains(e.message, "did you mean")) << e.message;
  e = single_error(schema, 5);
  EXPECT_FALSE(contains(e.message, "did you mean")) << e.message;
}

TEST(JsonSchemaEnum, NoSuggestionForTinyWords) {
  const Error e = single_error({{"enum", {"a", "b"}}}, "c");
  EXPECT_FALSE(contains(e.message, "did you mean")) << e.message;
}

TEST(JsonSchemaEnum, SingleValueEnumReadsLikeConst) {
  const Error e = single_error({{"enum", {"plate"}}}, "strip");
  EXPECT_TRUE(contains(e.message, "must be \"plate\" (got \"strip\")")) << e.message;
}

TEST(JsonSchemaConst, ComparesWholeValues) {
  EXPECT_TRUE(is_valid({{"const", 2}}, 2.0));
  EXPECT_TRUE(is_valid({{"const", {{"a", {1, 2}}}}}, {{"a", {1, 2}}}));
  EXPECT_FALSE(is_valid({{"const", {{"a", {1, 2}}}}}, {{"a", {2, 1}}}));
  EXPECT_TRUE(is_valid({{"const", nullptr}}, nullptr));
  EXPECT_FALSE(is_valid({{"const", nullptr}}, 0));
  const Error e = single_error({{"const", "v2"}}, "v1");
  EXPECT_TRUE(contains(e.message, "must be \"v2\"")) << e.message;
  EXPECT_TRUE(contains(e.message, "\"v1\"")) << e.message;
}

// ----------------------------------------------------------------- objects

TEST(JsonSchemaObject, RequiredPointsAtTheMissingMember) {
  const json schema = {
      {"type", "object"},
      {"required", {"scene"}},
      {"properties", {{"scene", {{"type", "object"}, {"required", {"type", "size"}}}}}}};
  EXPECT_TRUE(has_error(errors_of(schema, json::object()), "/scene", {"is required"}));
  const auto errors = errors_of(schema, {{"scene", json::object()}});
  ASSERT_EQ(errors.size(), 2u) << describe(errors);
  EXPECT_EQ(errors[0].pointer, "/scene/size");
  EXPECT_EQ(errors[1].pointer, "/scene/type");
  EXPECT_EQ(errors[1].message, "is required");
}

TEST(JsonSchemaObject, PointersEscapeMemberNames) {
  const json schema = {{"required", {"a/b", "c~d"}},
                       {"properties", {{"x/y", {{"type", "number"}}}}}};
  const auto errors = errors_of(schema, {{"x/y", "no"}});
  EXPECT_TRUE(has_error(errors, "/a~1b", {"is required"}));
  EXPECT_TRUE(has_error(errors, "/c~0d", {"is required"}));
  EXPECT_TRUE(has_error(errors, "/x~1y", {"must be a number"}));
}

TEST(JsonSchemaObject, PropertiesValidateOnlyPresentMembers) {
  const json schema = {{"properties", {{"n", {{"type", "integer"}}}}}};
  EXPECT_TRUE(is_valid(schema, json::object()));
  EXPECT_TRUE(is_valid(schema, {{"other", "x"}}));
  EXPECT_TRUE(is_valid(schema, "not an object"));  // no "type": other kinds pass
  EXPECT_TRUE(has_error(errors_of(schema, {{"n", "x"}}), "/n", {"integer"}));
}

TEST(JsonSchemaObject, AdditionalPropertiesFalseListsKnownFields) {
  const json schema = {{"properties",
                        {{"density", json::object()},
                         {"youngs_modulus", json::object()},
                         {"poisson_ratio", json::object()}}},
                       {"additionalProperties", false}};
  EXPECT_TRUE(is_valid(schema, {{"density", 1}}));
  const Error e = single_error(schema, {{"densty", 7800}});
  EXPECT_EQ(e.pointer, "/densty");
  EXPECT_TRUE(contains(e.message, "is not a known field here")) << e.message;
  EXPECT_TRUE(contains(e.message, "known fields: density, poisson_ratio, youngs_modulus"))
      << e.message;
  EXPECT_TRUE(contains(e.message, "did you mean \"density\"?")) << e.message;

  const Error far = single_error(schema, {{"colour", "red"}});
  EXPECT_FALSE(contains(far.message, "did you mean")) << far.message;
}

TEST(JsonSchemaObject, AdditionalPropertiesFalseWithoutAnyFields) {
  const Error e = single_error({{"additionalProperties", false}}, {{"x", 1}});
  EXPECT_EQ(e.pointer, "/x");
  EXPECT_TRUE(contains(e.message, "not allowed")) << e.message;
}

TEST(JsonSchemaObject, AdditionalPropertiesSchema) {
  const json schema = {{"properties", {{"name", {{"type", "string"}}}}},
                       {"additionalProperties", {{"type", "number"}}}};
  EXPECT_TRUE(is_valid(schema, {{"name", "x"}, {"a", 1}, {"b", 2.5}}));
  EXPECT_TRUE(has_error(errors_of(schema, {{"name", "x"}, {"a", "1"}}), "/a", {"number"}));
}

TEST(JsonSchemaObject, PatternProperties) {
  const json schema = {{"patternProperties", {{"^body_", {{"type", "object"}}}}},
                       {"properties", {{"name", {{"type", "string"}}}}},
                       {"additionalProperties", false}};
  EXPECT_TRUE(is_valid(schema, {{"name", "x"}, {"body_1", json::object()}}));
  auto errors = errors_of(schema, {{"body_1", 3}});
  EXPECT_TRUE(has_error(errors, "/body_1", {"must be an object"}));
  errors = errors_of(schema, {{"gear", json::object()}});
  EXPECT_TRUE(has_error(errors, "/gear", {"not a known field", "name", "^body_"}));
}

TEST(JsonSchemaObject, PatternPropertiesAndPropertiesBothApply) {
  const json schema = {{"properties", {{"ab", {{"minimum", 0}}}}},
                       {"patternProperties", {{"b$", {{"maximum", 10}}}}}};
  EXPECT_TRUE(is_valid(schema, {{"ab", 5}}));
  EXPECT_TRUE(has_error(errors_of(schema, {{"ab", -1}}), "/ab", {"at least 0"}));
  EXPECT_TRUE(has_error(errors_of(schema, {{"ab", 11}}), "/ab", {"at most 10"}));
}

TEST(JsonSchemaObject, PropertyNames) {
  const json schema = {{"propertyNames", {{"pattern", "^[a-z_]+$"}, {"maxLength", 8}}}};
  EXPECT_TRUE(is_valid(schema, {{"ok_name", 1}}));
  auto errors = errors_of(schema, {{"Bad", 1}});
  EXPECT_TRUE(has_error(errors, "/Bad", {"field name", "pattern", "^[a-z_]+$"}));
  errors = errors_of(schema, {{"much_too_long", 1}});
  EXPECT_TRUE(has_error(errors, "/much_too_long", {"field name", "at most 8 characters"}));
}

TEST(JsonSchemaObject, MinAndMaxProperties) {
  const json schema = {{"minProperties", 1}, {"maxProperties", 2}};
  EXPECT_TRUE(is_valid(schema, {{"a", 1}}));
  EXPECT_TRUE(has_error(errors_of(schema, json::object()), "", {"at least 1 field"}));
  EXPECT_TRUE(has_error(errors_of(schema, {{"a", 1}, {"b", 2}, {"c", 3}}), "",
                        {"at most 2 fields", "got 3"}));
}

// ------------------------------------------------------------------ arrays

TEST(JsonSchemaArray, ItemsApplyToEveryElement) {
  const json schema = {{"items", {{"type", "number"}, {"minimum", 0}}}};
  EXPECT_TRUE(is_valid(schema, json::array({0, 1.5, 2})));
  const auto errors = errors_of(schema, json::array({1, "x", -3}));
  ASSERT_EQ(errors.size(), 2u) << describe(errors);
  EXPECT_TRUE(has_error(errors, "/1", {"must be a number"}));
  EXPECT_TRUE(has_error(errors, "/2", {"at least 0", "got -3"}));
}

TEST(JsonSchemaArray, TupleItemsAndAdditionalItems) {
  const json tuple = {{"items", {{{"type", "string"}}, {{"type", "number"}}}}};
  EXPECT_TRUE(is_valid(tuple, json::array({"x", 1, true})));  // extras are free by default
  EXPECT_TRUE(is_valid(tuple, json::array({"x"})));           // missing items are fine
  EXPECT_TRUE(has_error(errors_of(tuple, json::array({1, 1})), "/0", {"must be a string"}));

  json closed = tuple;
  closed["additionalItems"] = false;
  EXPECT_TRUE(is_valid(closed, json::array({"x", 1})));
  EXPECT_TRUE(
      has_error(errors_of(closed, json::array({"x", 1, 2})), "", {"at most 2 items", "got 3"}));

  json typed = tuple;
  typed["additionalItems"] = {{"type", "boolean"}};
  EXPECT_TRUE(is_valid(typed, json::array({"x", 1, true, false})));
  EXPECT_TRUE(has_error(errors_of(typed, json::array({"x", 1, true, 4})), "/3", {"boolean"}));
}

TEST(JsonSchemaArray, AdditionalItemsIgnoredWithSingleItemsSchema) {
  EXPECT_TRUE(
      is_valid({{"items", json::object()}, {"additionalItems", false}}, json::array({1, 2, 3})));
}

TEST(JsonSchemaArray, MinAndMaxItems) {
  const json schema = {{"minItems", 2}, {"maxItems", 3}};
  EXPECT_TRUE(is_valid(schema, json::array({1, 2})));
  EXPECT_TRUE(has_error(errors_of(schema, json::array({1})), "", {"at least 2 items", "got 1"}));
  EXPECT_TRUE(has_error(errors_of(schema, json::array()), "", {"empty", "at least 2 items"}));
  EXPECT_TRUE(
      has_error(errors_of(schema, json::array({1, 2, 3, 4})), "", {"at most 3 items", "got 4"}));
  EXPECT_TRUE(has_error(errors_of({{"maxItems", 1}}, json::array({1, 2})), "", {"at most 1 item"}));
}

TEST(JsonSchemaArray, UniqueItems) {
  const json schema = {{"uniqueItems", true}};
  EXPECT_TRUE(is_valid(schema, json::array({1, "1", json::array({1}), json::object()})));
  EXPECT_TRUE(is_valid({{"uniqueItems", false}}, json::array({1, 1})));
  auto errors = errors_of(schema, json::array({1, 2, 1.0, 3, 2}));
  ASSERT_EQ(errors.size(), 2u) << describe(errors);
  EXPECT_TRUE(has_error(errors, "/2", {"repeats item 0", "different"}));
  EXPECT_TRUE(has_error(errors, "/4", {"repeats item 1"}));
  errors = errors_of(schema, json::array({{{"a", 1}}, {{"a", 1}}}));
  EXPECT_TRUE(has_error(errors, "/1", {"repeats item 0"}));
}

TEST(JsonSchemaArray, Contains) {
  const json schema = {{"contains", {{"type", "string"}}}};
  EXPECT_TRUE(is_valid(schema, json::array({1, "x"})));
  EXPECT_TRUE(has_error(errors_of(schema, json::array({1, 2})), "",
                        {"must contain at least one item", "a string"}));
  EXPECT_TRUE(has_error(errors_of(schema, json::array()), "", {"empty"}));
  EXPECT_TRUE(has_error(errors_of({{"contains", {{"minimum", 5}}}}, json::array({1})), "",
                        {"must contain at least one item"}));
}

// ----------------------------------------------------------------- numbers

TEST(JsonSchemaNumber, InclusiveBounds) {
  const json schema = {{"minimum", 0.0001}, {"maximum", 0.5}};
  EXPECT_TRUE(is_valid(schema, 0.0001));
  EXPECT_TRUE(is_valid(schema, 0.5));
  Error e = single_error(schema, 0);
  EXPECT_EQ(e.message, "must be at least 0.0001 (got 0)");
  e = single_error(schema, 0.7);
  EXPECT_EQ(e.message, "must be at most 0.5 (got 0.7)");
}

TEST(JsonSchemaNumber, ExclusiveBounds) {
  const json schema = {{"exclusiveMinimum", 0}, {"exclusiveMaximum", 1}};
  EXPECT_TRUE(is_valid(schema, 0.5));
  Error e = single_error(schema, -2);
  EXPECT_EQ(e.message, "must be greater than 0 (got -2)");
  e = single_error(schema, 0);
  EXPECT_TRUE(contains(e.message, "greater than 0")) << e.message;
  e = single_error(schema, 1);
  EXPECT_TRUE(contains(e.message, "must be less than 1 (got 1)")) << e.message;
}

TEST(JsonSchemaNumber, LargeIntegers) {
  // valijson compares bounds as doubles: 2^53 + 1 and 2^53 + 2 round apart.
  const json schema = {{"maximum", json::parse("9007199254740993")}};
  EXPECT_TRUE(is_valid(schema, json::parse("9007199254740993")));
  EXPECT_FALSE(is_valid(schema, json::parse("9007199254740994")));
  EXPECT_TRUE(is_valid({{"minimum", -1}}, json::parse("18446744073709551615")));
  EXPECT_TRUE(is_valid({{"maximum", json::parse("18446744073709551615")}}, -5));
}

TEST(JsonSchemaNumber, MultipleOf) {
  // valijson allows a remainder of one machine epsilon: 0.3 is a multiple of
  // 0.1, 4.35 is not quite one of 0.01.
  EXPECT_TRUE(is_valid({{"multipleOf", 0.1}}, 0.3));
  EXPECT_TRUE(is_valid({{"multipleOf", 3}}, -9));
  EXPECT_TRUE(is_valid({{"multipleOf", 2}}, 4.0));
  EXPECT_TRUE(is_valid({{"multipleOf", 0.5}}, 1e300));
  EXPECT_FALSE(is_valid({{"multipleOf", 3}}, 10));
  EXPECT_FALSE(is_valid({{"multipleOf", 0.1}}, 0.35));
  const Error e = single_error({{"multipleOf", 0.5}}, 0.7);
  EXPECT_EQ(e.message, "must be a multiple of 0.5 (got 0.7)");
}

TEST(JsonSchemaNumber, NumbersArePrintedCompactly) {
  auto message = [](const json& bound, const json& value) {
    return single_error({{"maximum", bound}}, value).message;
  };
  EXPECT_TRUE(contains(message(4e-8, 1), "at most 4e-08 ")) << message(4e-8, 1);
  EXPECT_TRUE(contains(message(0.353, 1), "at most 0.353 ")) << message(0.353, 1);
  EXPECT_TRUE(contains(message(1000.0, 2000), "at most 1000 (got 2000)")) << message(1000.0, 2000);
  EXPECT_TRUE(contains(message(1.73e11, 2e11), "at most 1.73e+11 (got 2e+11)"))
      << message(1.73e11, 2e11);
  EXPECT_TRUE(contains(message(0.1, 0.30000000000000004), "(got 0.30000000000000004)"));
  EXPECT_FALSE(contains(message(1e-9, 1e-7), "0.000000")) << message(1e-9, 1e-7);
  EXPECT_TRUE(contains(message(-1, 2), "at most -1 (got 2)")) << message(-1, 2);
}

// ----------------------------------------------------------------- strings

TEST(JsonSchemaString, LengthCountsCodePoints) {
  const json schema = {{"minLength", 2}, {"maxLength", 5}};
  EXPECT_TRUE(is_valid(schema, "h\u00e9llo"));                        // 5 code points, 6 bytes
  EXPECT_TRUE(is_valid(schema, "\xF0\x9F\x98\x80\xF0\x9F\x98\x80"));  // two emoji
  EXPECT_FALSE(is_valid(schema, "\xF0\x9F\x98\x80"));                 // one emoji, 4 bytes
  EXPECT_TRUE(has_error(errors_of(schema, "a"), "", {"at least 2 characters", "\"a\""}));
  EXPECT_TRUE(
      has_error(errors_of(schema, "abcdefg"), "", {"at most 5 characters", "got 7 characters"}));
  EXPECT_TRUE(has_error(errors_of(schema, ""), "", {"must not be empty"}));
}

TEST(JsonSchemaString, PatternUsesSearchSemantics) {
  EXPECT_TRUE(is_valid({{"pattern", "b"}}, "abc"));
  EXPECT_FALSE(is_valid({{"pattern", "^b"}}, "abc"));
  EXPECT_TRUE(is_valid({{"pattern", "^[a-z]+(_[a-z0-9]+)*$"}}, "strip_wave2"));
  const Error e = single_error({{"pattern", "^[a-z]+$"}}, "ABC");
  EXPECT_TRUE(contains(e.message, "must match the pattern \"^[a-z]+$\"")) << e.message;
  EXPECT_TRUE(contains(e.message, "\"ABC\"")) << e.message;
  EXPECT_TRUE(is_valid({{"pattern", "^x"}}, 5));  // only strings are matched
}

TEST(JsonSchemaString, VeryLongSubjectsAreReportedNotMatched) {
  // libstdc++'s regex recurses per character; such strings would risk the stack.
  const json schema = {{"pattern", "(a|b)*c"}};
  EXPECT_TRUE(is_valid(schema, std::string(900, 'a') + "c"));
  EXPECT_TRUE(has_error(errors_of(schema, std::string(100000, 'a')), "", {"too long", "pattern"}));
}

// ------------------------------------------------------------- combinators

TEST(JsonSchemaCombinators, AllOfReportsEveryBranch) {
  const json schema = {{"allOf", {{{"minimum", 10}}, {{"multipleOf", 3}}}}};
  EXPECT_TRUE(is_valid(schema, 12));
  const auto errors = errors_of(schema, 5);
  EXPECT_EQ(errors.size(), 2u) << describe(errors);
  EXPECT_TRUE(has_error(errors, "", {"at least 10"}));
  EXPECT_TRUE(has_error(errors, "", {"multiple of 3"}));
}

TEST(JsonSchemaCombinators, AnyOfReportsTheClosestBranch) {
  const json schema = {{"anyOf",
                        {{{"required", {"a", "b", "c"}}},  // three errors for {}
                         {{"required", {"x"}}}}}};         // one error for {}
  EXPECT_TRUE(is_valid(schema, {{"x", 1}}));
  const auto errors = errors_of(schema, json::object());
  ASSERT_EQ(errors.size(), 1u) << describe(errors);
  EXPECT_EQ(errors[0].pointer, "/x");
  EXPECT_EQ(errors[0].message, "is required");
}

TEST(JsonSchemaCombinators, AnyOfTieGoesToTheFirstBranch) {
  const json schema = {{"anyOf", {{{"required", {"first"}}}, {{"required", {"second"}}}}}};
  const auto errors = errors_of(schema, json::object());
  ASSERT_EQ(errors.size(), 1u) << describe(errors);
  EXPECT_EQ(errors[0].pointer, "/first");
}

TEST(JsonSchemaCombinators, AnyOfMergesKindMismatchesIntoOneMessage) {
  const json schema = {{"anyOf", {{{"type", "number"}}, {{"type", "array"}}}}};
  const Error e = single_error(schema, "abc");
  EXPECT_EQ(e.message, "must be a number or an array, not a string (\"abc\")");

  const json with_const = {{"anyOf", {{{"type", "number"}}, {{"const", "auto"}}}}};
  EXPECT_TRUE(is_valid(with_const, "auto"));
  const Error c = single_error(with_const, "autp");
  EXPECT_TRUE(contains(c.message, "a number or \"auto\"")) << c.message;
  EXPECT_TRUE(contains(c.message, "did you mean \"auto\"?")) << c.message;
}

TEST(JsonSchemaCombinators, AnyOfPrefersTheBranchOfTheRightKind) {
  // A material is a name or an object; an object with two bad fields should
  // be told about those fields, not that it should have been a string.
  const json schema = {
      {"anyOf",
       {{{"type", "string"}},
        {{"type", "object"},
         {"properties", {{"density", {{"minimum", 0}}}, {"nu", {{"maximum", 0.5}}}}}}}}};
  const auto errors = errors_of(schema, {{"density", -1}, {"nu", 0.7}});
  EXPECT_EQ(errors.size(), 2u) << describe(errors);
  EXPECT_TRUE(has_error(errors, "/density", {"at least 0"}));
  EXPECT_TRUE(has_error(errors, "/nu", {"at most 0.5"}));
}

TEST(JsonSchemaCombinators, OneOfExactlyOne) {
  const json schema = {{"oneOf", {{{"multipleOf", 2}}, {{"multipleOf", 3}}}}};
  EXPECT_TRUE(is_valid(schema, 4));
  EXPECT_TRUE(is_valid(schema, 9));
  EXPECT_TRUE(has_error(errors_of(schema, 6), "", {"matches more than one of the allowed forms"}));
  EXPECT_TRUE(has_error(errors_of(schema, 7), "", {"multiple of 2"}));
}

TEST(JsonSchemaCombinators, OneOfNamesOverlappingBranchesByTitle) {
  const json schema = {
      {"oneOf", {{{"title", "Small"}, {"maximum", 10}}, {{"title", "Even"}, {"multipleOf", 2}}}}};
  const Error e = single_error(schema, 4);
  EXPECT_TRUE(contains(e.message, "more than one")) << e.message;
  EXPECT_TRUE(contains(e.message, "\"Small\"")) << e.message;
  EXPECT_TRUE(contains(e.message, "\"Even\"")) << e.message;
}

TEST(JsonSchemaCombinators, OneOfWithDiscriminatorReportsTheIntendedBranch) {
  const json plate = {
      {"type", "object"},
      {"required", {"type", "thickness"}},
      {"properties", {{"type", {{"const", "plate"}}}, {"thickness", {{"exclusiveMinimum", 0}}}}}};
  const json strip = {{"type", "object"},
                      {"required", {"type", "width", "amplitude"}},
                      {"properties",
                       {{"type", {{"const", "strip_wave"}}},
                        {"width", {{"exclusiveMinimum", 0}}},
                        {"amplitude", {{"minimum", 0}}}}}};
  const json schema = {{"oneOf", {plate, strip}}};
  const auto errors = errors_of(schema, {{"type", "strip_wave"}, {"width", -1}, {"amplitude", -1}});
  EXPECT_EQ(errors.size(), 2u) << describe(errors);
  EXPECT_TRUE(has_error(errors, "/width", {"greater than 0"}));
  EXPECT_TRUE(has_error(errors, "/amplitude", {"at least 0"}));
}

TEST(JsonSchemaCombinators, Not) {
  EXPECT_TRUE(is_valid({{"not", {{"type", "string"}}}}, 1));
  Error e = single_error({{"not", {{"type", "string"}}}}, "x");
  EXPECT_TRUE(contains(e.message, "must not be a string")) << e.message;
  e = single_error({{"not", {{"const", 0}}}}, 0);
  EXPECT_TRUE(contains(e.message, "must not be 0")) << e.message;
  e = single_error({{"not", {{"enum", {"a", "b"}}}}}, "a");
  EXPECT_TRUE(contains(e.message, "must not be one of \"a\", \"b\"")) << e.message;
  e = single_error({{"not", {{"required", {"x"}}}}}, {{"x", 1}});
  EXPECT_TRUE(contains(e.message, "must not have the field \"x\"")) << e.message;
  e = single_error({{"not", {{"required", {"x", "y"}}}}}, {{"x", 1}, {"y", 2}});
  EXPECT_TRUE(contains(e.message, "\"x\" and \"y\"")) << e.message;
  e = single_error({{"not", {{"title", "legacy layout"}, {"minProperties", 3}}}},
                   {{"a", 1}, {"b", 2}, {"c", 3}});
  EXPECT_TRUE(contains(e.message, "must not match \"legacy layout\"")) << e.message;
  e = single_error({{"not", true}}, 1);
  EXPECT_TRUE(contains(e.message, "must not")) << e.message;
}

TEST(JsonSchemaCombinators, IfThenElseReportsBranchErrorsAsTheyAre) {
  const json schema = {
      {"if", {{"properties", {{"kind", {{"const", "disk"}}}}}}},
      {"then", {{"required", {"radius"}}}},
      {"else", {{"required", {"width"}}}},
  };
  EXPECT_TRUE(is_valid(schema, {{"kind", "disk"}, {"radius", 1}}));
  EXPECT_TRUE(is_valid(schema, {{"kind", "plate"}, {"width", 1}}));
  auto errors = errors_of(schema, {{"kind", "disk"}});
  ASSERT_EQ(errors.size(), 1u) << describe(errors);
  EXPECT_EQ(errors[0].pointer, "/radius");
  EXPECT_EQ(errors[0].message, "is required");
  errors = errors_of(schema, {{"kind", "plate"}});
  ASSERT_EQ(errors.size(), 1u) << describe(errors);
  EXPECT_EQ(errors[0].pointer, "/width");
}

TEST(JsonSchemaCombinators, IfWithoutBranchesAndBranchesWithoutIf) {
  EXPECT_TRUE(is_valid({{"if", {{"type", "string"}}}}, 1));
  EXPECT_TRUE(is_valid({{"then", false}, {"else", false}}, 1));  // no "if": ignored
  EXPECT_TRUE(is_valid({{"if", {{"type", "string"}}}, {"then", {{"minLength", 1}}}}, 5));
}

// -------------------------------------------------------------------- $ref

TEST(JsonSchemaRef, Definitions) {
  const json schema = {
      {"definitions", {{"positive", {{"type", "number"}, {"exclusiveMinimum", 0}}}}},
      {"properties", {{"dt", {{"$ref", "#/definitions/positive"}}}}}};
  EXPECT_TRUE(is_valid(schema, {{"dt", 1e-6}}));
  EXPECT_TRUE(has_error(errors_of(schema, {{"dt", 0}}), "/dt", {"greater than 0"}));
}

TEST(JsonSchemaRef, RecursiveRootReference) {
  const json tree = {{"type", "object"},
                     {"properties",
                      {{"value", {{"type", "number"}}},
                       {"children", {{"type", "array"}, {"items", {{"$ref", "#"}}}}}}}};
  const json instance = {
      {"value", 1}, {"children", {{{"value", 2}}, {{"value", "x"}, {"children", json::array()}}}}};
  EXPECT_TRUE(has_error(errors_of(tree, instance), "/children/1/value", {"must be a number"}));
}

TEST(JsonSchemaRef, ArbitraryPointersWithEscapes) {
  const json schema = {{"definitions",
                        {{"a/b", {{"type", "string"}}},
                         {"m~n", {{"type", "integer"}}},
                         {"sp ace", {{"minimum", 1}}}}},
                       {"properties",
                        {{"p", {{"$ref", "#/definitions/a~1b"}}},
                         {"q", {{"$ref", "#/definitions/m~0n"}}},
                         {"r", {{"$ref", "#/properties/q"}}},
                         {"s", {{"$ref", "#/definitions/sp%20ace"}}},
                         {"t", {{"$ref", "#/allOf/0"}}}}},
                       {"allOf", {{{"type", "object"}}}}};
  EXPECT_TRUE(is_valid(schema, {{"p", "x"}, {"q", 1}, {"r", 2}, {"s", 3}, {"t", json::object()}}));
  const auto errors = errors_of(schema, {{"p", 1}, {"q", "x"}, {"r", 1.5}, {"s", 0}, {"t", 1}});
  EXPECT_EQ(errors.size(), 5u) << describe(errors);
  EXPECT_TRUE(has_error(errors, "/p", {"string"}));
  EXPECT_TRUE(has_error(errors, "/q", {"integer"}));
  EXPECT_TRUE(has_error(errors, "/r", {"integer"}));
  EXPECT_TRUE(has_error(errors, "/s", {"at least 1"}));
  EXPECT_TRUE(has_error(errors, "/t", {"object"}));
}

TEST(JsonSchemaRef, LongReferenceChains) {
  // Built with append: `"d" + std::to_string(i)` trips GCC 12's -Wrestrict at -O3.
  const auto name = [](const char* prefix, int i) {
    std::string text = prefix;
    text += std::to_string(i);
    return text;
  };
  json definitions = {{"d0", {{"type", "integer"}, {"default", 5}}}};
  for (int i = 1; i <= 150; ++i) {
    definitions[name("d", i)] = {{"$ref", name("#/definitions/d", i - 1)}};
  }
  const Validator validator(json{{"definitions", definitions},
                                 {"properties", {{"x", {{"$ref", "#/definitions/d150"}}}}}});
  EXPECT_TRUE(validator.validate({{"x", 1}}).empty());
  EXPECT_TRUE(has_error(validator.validate({{"x", "one"}}), "/x", {"must be an integer"}));
  EXPECT_EQ(validator.apply_defaults(json::object()), json({{"x", 5}}));
}

TEST(JsonSchemaRef, SiblingKeywordsAreIgnoredAsInDraft7) {
  const json schema = {{"definitions", {{"list", {{"type", "array"}}}}},
                       {"properties", {{"xs", {{"$ref", "#/definitions/list"}, {"maxItems", 1}}}}}};
  EXPECT_TRUE(is_valid(schema, {{"xs", {1, 2, 3}}}));
}

TEST(JsonSchemaRef, UnresolvableReferencesThrow) {
  EXPECT_THROW(Validator(json{{"$ref", "#/definitions/missing"}}), std::invalid_argument);
  EXPECT_THROW(Validator(json{{"$ref", "other.json#/a"}}), std::invalid_argument);
  EXPECT_THROW(Validator(json{{"$ref", "#anchor"}}), std::invalid_argument);
  EXPECT_THROW(Validator(json{{"$ref", 5}}), std::invalid_argument);
  EXPECT_THROW(
      Validator(json{{"$ref", "#/definitions/bad~2escape"}, {"definitions", json::object()}}),
      std::invalid_argument);
  EXPECT_THROW(Validator(json{{"items", {{"$ref", "#/allOf/1"}}}, {"allOf", {true}}}),
               std::invalid_argument);
  EXPECT_THROW(Validator(json{{"definitions", {{"x", {{"$ref", "#/nope"}}}}}}),
               std::invalid_argument);  // even when never used
  try {
    Validator(json{{"properties", {{"a", {{"$ref", "#/definitions/gear"}}}}}});
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_TRUE(contains(e.what(), "#/definitions/gear")) << e.what();
    EXPECT_TRUE(contains(e.what(), "#/properties/a")) << e.what();
  }
}

TEST(JsonSchemaRef, ReferenceLoopsThrow) {
  EXPECT_THROW(Validator(json{{"$ref", "#"}}), std::invalid_argument);
  EXPECT_THROW(
      Validator(json{{"definitions",
                      {{"a", {{"$ref", "#/definitions/b"}}}, {"b", {{"$ref", "#/definitions/a"}}}}},
                     {"$ref", "#/definitions/a"}}),
      std::invalid_argument);
}

TEST(JsonSchemaRef, SchemaRecursionWithoutProgressIsRefused) {
  // Each level would re-check the same value: no instance depth is consumed.
  EXPECT_THROW(Validator(json{{"allOf", {{{"$ref", "#"}}}}}), std::invalid_argument);
  EXPECT_THROW(Validator(json{
                   {"anyOf", {{{"$ref", "#"}, {"title", "a"}}, {{"$ref", "#"}, {"title", "b"}}}}}),
               std::invalid_argument);
  EXPECT_THROW(Validator(json{{"not", {{"if", {{"$ref", "#"}}}}}}), std::invalid_argument);
  EXPECT_THROW(
      Validator(json{{"definitions", {{"a", {{"dependencies", {{"x", {{"$ref", "#"}}}}}}}}},
                     {"allOf", {{{"$ref", "#/definitions/a"}}}}}),
      std::invalid_argument);
  // Descending into the value between two visits is fine.
  EXPECT_NO_THROW(Validator(json{{"anyOf", {{{"items", {{"$ref", "#"}}}}, {{"type", "null"}}}}}));
}

TEST(JsonSchemaRef, LargeInstances) {
  const Validator validator(
      json{{"definitions", {{"point", {{"type", "array"}, {"items", {{"type", "number"}}}}}}},
           {"type", "array"},
           {"items", {{"allOf", {{{"$ref", "#/definitions/point"}}, {{"minItems", 2}}}}}}});
  const json points(std::vector<std::vector<double>>(100000, {0.5, 1.5}));
  EXPECT_TRUE(validator.validate(points).empty());
}

// ------------------------------------------------------- malformed schemas

TEST(JsonSchemaMalformed, RejectsBadKeywordValues) {
  const std::vector<json> bad = {
      json(5),
      json("string"),
      json::array(),
      {{"type", "float"}},
      {{"type", json::array()}},
      {{"type", 5}},
      {{"enum", "a"}},
      {{"minimum", "0"}},
      {{"exclusiveMinimum", true}},  // the draft-04 form
      {{"multipleOf", 0}},
      {{"multipleOf", -1}},
      {{"minLength", -1}},
      {{"maxItems", 1.5}},
      {{"required", "a"}},
      {{"required", {1}}},
      {{"properties", json::array()}},
      {{"properties", {{"a", 5}}}},
      {{"items", "x"}},
      {{"items", {true, 3}}},
      {{"allOf", json::array()}},
      {{"anyOf", {{{"type", "wat"}}}}},
      {{"oneOf", json::object()}},
      {{"not", 1}},
      {{"uniqueItems", "yes"}},
      {{"pattern", 5}},
      {{"definitions", {{"x", "y"}}}},
  };
  for (const auto& schema : bad) {
    EXPECT_THROW(Validator{schema}, std::invalid_argument) << schema.dump();
  }
}

TEST(JsonSchemaMalformed, InvalidRegexThrowsAtConstruction) {
  EXPECT_THROW(Validator(json{{"pattern", "([a-z"}}), std::invalid_argument);
  EXPECT_THROW(Validator(json{{"patternProperties", {{"*bad", true}}}}), std::invalid_argument);
  EXPECT_THROW(Validator(json{{"propertyNames", {{"pattern", "a{2,1}"}}}}), std::invalid_argument);
  try {
    Validator(json{{"properties", {{"name", {{"pattern", "(x"}}}}}});
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_TRUE(contains(e.what(), "#/properties/name")) << e.what();
    EXPECT_TRUE(contains(e.what(), "(x")) << e.what();
  }
}

TEST(JsonSchemaMalformed, AcceptsIntegralFloatsForCounts) {
  EXPECT_NO_THROW(Validator(json{{"minItems", 2.0}}));
  EXPECT_FALSE(is_valid({{"minItems", 2.0}}, json::array({1})));
}

// ----------------------------------------------------------- error listing

TEST(JsonSchemaErrors, SortedDeduplicatedAndCapped) {
  const json schema = {{"properties",
                        {{"b", {{"type", "string"}}},
                         {"a", {{"allOf", {{{"type", "string"}}, {{"type", "string"}}}}}},
                         {"c", {{"items", {{"type", "string"}}}}}}}};
  const json instance = {{"c", {1, 2, 3}}, {"b", 1}, {"a", 1}};
  const auto errors = Validator(schema).validate(instance);
  ASSERT_EQ(errors.size(), 5u) << describe(errors);  // /a is reported once
  EXPECT_TRUE(std::is_sorted(errors.begin(), errors.end(),
                             [](const Error& x, const Error& y) { return x.pointer < y.pointer; }));
  EXPECT_EQ(errors[0].pointer, "/a");
  EXPECT_EQ(errors[1].pointer, "/b");
  EXPECT_EQ(errors[2].pointer, "/c/0");

  const auto capped = Validator(schema).validate(instance, 2);
  ASSERT_EQ(capped.size(), 2u);
  EXPECT_EQ(capped[0], errors[0]);
  EXPECT_EQ(capped[1], errors[1]);
  EXPECT_TRUE(Validator(schema).validate(instance, 0).empty());
}

TEST(JsonSchemaErrors, StableOrderForOnePointer) {
  const json schema = {{"minimum", 10}, {"multipleOf", 3}};
  const auto errors = errors_of(schema, 5);
  ASSERT_EQ(errors.size(), 2u);
  EXPECT_TRUE(contains(errors[0].message, "at least 10"));
  EXPECT_TRUE(contains(errors[1].message, "multiple of 3"));
}

TEST(JsonSchemaErrors, ManyErrorsDefaultToFifty) {
  const json schema = {{"items", {{"type", "string"}}}};
  EXPECT_EQ(Validator(schema).validate(json(std::vector<int>(500, 1))).size(), 50u);
}

// --------------------------------------------------------------- recursion

json nested_arrays(int depth) {
  json value = json::array();
  for (int i = 0; i < depth; ++i) value = json::array({std::move(value)});
  return value;
}

// "/0/0/...": the first item `levels` deep in nested_arrays().
std::string deep_pointer(int levels) {
  std::string pointer;
  for (int i = 0; i < levels; ++i) pointer += "/0";
  return pointer;
}

TEST(JsonSchemaRecursion, DeepInstancesGetAnErrorNotACrash) {
  const Validator validator(json{{"type", "array"}, {"items", {{"$ref", "#"}}}});
  EXPECT_TRUE(validator.validate(nested_arrays(50)).empty());
  const auto errors = validator.validate(nested_arrays(5000));
  ASSERT_EQ(errors.size(), 1u) << describe(errors);
  EXPECT_TRUE(contains(errors[0].message, "nested too deeply"));
  EXPECT_EQ(std::count(errors[0].pointer.begin(), errors[0].pointer.end(), '/'), 201);
  EXPECT_NO_THROW(validator.apply_defaults(nested_arrays(5000)));
}

TEST(JsonSchemaRecursion, DeepValuesInComparisonsAndMessages) {
  // json's ==, < and dump recurse per level; deep values never reach them.
  json pair = json::array();
  pair.push_back(nested_arrays(20000));
  pair.push_back(nested_arrays(20000));
  const auto errors = Validator(json{{"uniqueItems", true}}).validate(pair);
  ASSERT_EQ(errors.size(), 2u) << describe(errors);
  EXPECT_TRUE(contains(errors[0].message, "nested too deeply")) << describe(errors);
  const json shallow_pair = json::array({json::array({1}), json::array({1})});
  EXPECT_TRUE(has_error(Validator(json{{"uniqueItems", true}}).validate(shallow_pair), "/1",
                        {"repeats item 0"}));

  const Error deep = single_error(json{{"const", 1}}, nested_arrays(20000));
  EXPECT_TRUE(contains(deep.message, "nested too deeply")) << deep.message;
  const Error wide = single_error(json{{"const", 1}}, json(std::vector<int>(100000, 7)));
  EXPECT_TRUE(contains(wide.message, "an array of 100000 items")) << wide.message;
  const Error small = single_error(json{{"const", 1}}, {{"a", {1, 2}}});
  EXPECT_TRUE(contains(small.message, "(got {\"a\":[1,2]})")) << small.message;
  const Error nested = single_error(json{{"const", 1}}, nested_arrays(150));
  EXPECT_TRUE(contains(nested.message, "must be 1 (got an array of 1 item)")) << nested.message;
}

TEST(JsonSchemaRecursion, ApplyDefaultsCopiesDeepInstancesWithoutRecursion) {
  const json deep = nested_arrays(100000);
  json copy;
  ASSERT_NO_THROW(copy = Validator(true).apply_defaults(deep));
  EXPECT_TRUE(copy.is_array());
  // Compare the spine iteratively (json's == would recurse).
  const json* a = &deep;
  const json* b = &copy;
  int levels = 0;
  while (!a->empty()) {
    ASSERT_EQ(b->size(), 1u);
    a = &(*a)[0];
    b = &(*b)[0];
    ++levels;
  }
  EXPECT_EQ(levels, 100000);
  EXPECT_TRUE(b->empty());
}

TEST(JsonSchemaRecursion, DeepInstancesAreRefusedWhateverTheSchema) {
  // valijson recurses per level of the instance, so no schema is given them.
  EXPECT_TRUE(has_error(Validator(true).validate(nested_arrays(5000)), deep_pointer(201),
                        {"nested too deeply"}));
  EXPECT_TRUE(Validator(true).validate(nested_arrays(200)).empty());
  EXPECT_FALSE(Validator(json{{"type", "array"}}).validate(nested_arrays(201)).empty());
}

// ---------------------------------------------------------------- defaults

TEST(JsonSchemaDefaults, FillsAbsentPropertiesOnly) {
  const Validator validator(json{{"properties",
                                  {{"dt", {{"default", 1e-6}}},
                                   {"steps", {{"default", 100}}},
                                   {"name", {{"type", "string"}}}}}});
  const json filled = validator.apply_defaults({{"steps", 5}});
  EXPECT_EQ(filled, json({{"dt", 1e-6}, {"steps", 5}}));
  EXPECT_EQ(validator.apply_defaults({{"dt", nullptr}})["dt"], nullptr);  // present: kept
}

TEST(JsonSchemaDefaults, NestedDefaultsFillDefaultedObjects) {
  const Validator validator(json{
      {"properties",
       {{"scene",
         {{"default", json::object()},
          {"properties",
           {{"type", {{"default", "plate"}}},
            {"size", {{"default", {{"x", 1}}}, {"properties", {{"y", {{"default", 2}}}}}}}}}}}}}});
  const json filled = validator.apply_defaults(json::object());
  EXPECT_EQ(filled, json({{"scene", {{"type", "plate"}, {"size", {{"x", 1}, {"y", 2}}}}}}));
  const json partial = validator.apply_defaults({{"scene", {{"type", "disk"}}}});
  EXPECT_EQ(partial["scene"]["type"], "disk");
  EXPECT_EQ(partial["scene"]["size"]["y"], 2);
}

TEST(JsonSchemaDefaults, FollowsRefsAndTakesDefaultsFromTargets) {
  const Validator validator(
      json{{"definitions",
            {{"material",
              {{"default", json::object()}, {"properties", {{"density", {{"default", 7800}}}}}}}}},
           {"properties",
            {{"gear", {{"$ref", "#/definitions/material"}}},
             {"rack", {{"$ref", "#/definitions/material"}, {"default", {{"density", 1}}}}}}}});
  const json filled = validator.apply_defaults(json::object());
  EXPECT_EQ(filled["gear"], json({{"density", 7800}}));
  EXPECT_EQ(filled["rack"], json({{"density", 1}}));  // the default next to the $ref wins
}

TEST(JsonSchemaDefaults, DefaultDiscriminatorSelectsItsBranch) {
  const json scene = {
      {"type", "object"},
      {"properties", {{"type", {{"enum", {"plate", "disk"}}, {"default", "plate"}}}}},
      {"if", {{"properties", {{"type", {{"const", "plate"}}}}}}},
      {"then", {{"properties", {{"thickness", {{"default", 0.01}}}}}}},
      {"else", {{"properties", {{"radius", {{"default", 0.5}}}}}}}};
  const Validator validator(json{{"properties", {{"scene", scene}}}});
  EXPECT_EQ(validator.apply_defaults({{"scene", json::object()}}),
            json({{"scene", {{"type", "plate"}, {"thickness", 0.01}}}}));
  EXPECT_EQ(validator.apply_defaults({{"scene", {{"type", "disk"}}}}),
            json({{"scene", {{"type", "disk"}, {"radius", 0.5}}}}));
}

TEST(JsonSchemaDefaults, AllOfAndFirstMatchingAnyOfBranch) {
  const Validator validator(
      json{{"allOf", {{{"properties", {{"a", {{"default", 1}}}}}}}},
           {"anyOf",
            {{{"required", {"disk"}}, {"properties", {{"r", {{"default", 2}}}}}},
             {{"properties", {{"w", {{"default", 3}}}}}},
             {{"properties", {{"never", {{"default", 4}}}}}}}}});
  EXPECT_EQ(validator.apply_defaults(json::object()), json({{"a", 1}, {"w", 3}}));
  EXPECT_EQ(validator.apply_defaults({{"disk", true}}), json({{"a", 1}, {"disk", true}, {"r", 2}}));
}

TEST(JsonSchemaDefaults, OneOfUsesTheFirstValidBranch) {
  const Validator validator(
      json{{"oneOf",
            {{{"properties", {{"kind", {{"const", "a"}}}, {"x", {{"default", 1}}}}},
              {"required", {"kind"}}},
             {{"properties", {{"kind", {{"const", "b"}}}, {"y", {{"default", 2}}}}},
              {"required", {"kind"}}}}}});
  EXPECT_EQ(validator.apply_defaults({{"kind", "b"}}), json({{"kind", "b"}, {"y", 2}}));
  EXPECT_EQ(validator.apply_defaults({{"kind", "c"}}), json({{"kind", "c"}}));
}

TEST(JsonSchemaDefaults, ArrayItemsAndMaps) {
  const Validator validator(
      json{{"properties",
            {{"bodies", {{"items", {{"properties", {{"mass", {{"default", 1}}}}}}}}},
             {"pair",
              {{"items", {{{"properties", {{"a", {{"default", 1}}}}}}}},
               {"additionalItems", {{"properties", {{"b", {{"default", 2}}}}}}}}},
             {"named", {{"additionalProperties", {{"properties", {{"c", {{"default", 3}}}}}}}}}}}});
  const json filled =
      validator.apply_defaults({{"bodies", {{{"mass", 5}}, json::object(), 7}},
                                {"pair", {json::object(), json::object(), json::object()}},
                                {"named", {{"x", json::object()}}}});
  EXPECT_EQ(filled["bodies"], json({{{"mass", 5}}, {{"mass", 1}}, 7}));
  EXPECT_EQ(filled["pair"], json({{{"a", 1}}, {{"b", 2}}, {{"b", 2}}}));
  EXPECT_EQ(filled["named"]["x"]["c"], 3);
}

TEST(JsonSchemaDefaults, InvalidInstancesAreLeftAlone) {
  const Validator validator(
      json{{"type", "object"},
           {"properties",
            {{"scene", {{"type", "object"}, {"properties", {{"t", {{"default", 1}}}}}}}}}});
  EXPECT_EQ(validator.apply_defaults("text"), "text");
  EXPECT_EQ(validator.apply_defaults({{"scene", 5}}), json({{"scene", 5}}));
  EXPECT_EQ(validator.apply_defaults(nullptr), nullptr);
  EXPECT_EQ(validator.apply_defaults(json::array({1})), json::array({1}));
}

TEST(JsonSchemaDefaults, DefaultsAreDeepCopies) {
  const Validator validator(json{{"properties", {{"v", {{"default", {{"list", {1, 2}}}}}}}}});
  json first = validator.apply_defaults(json::object());
  first["v"]["list"].push_back(3);
  EXPECT_EQ(validator.apply_defaults(json::object())["v"]["list"], json({1, 2}));
  EXPECT_EQ(validator.schema()["properties"]["v"]["default"]["list"], json({1, 2}));
}

TEST(JsonSchemaDefaults, RecursiveSchemaDefaults) {
  const Validator validator(json{
      {"properties", {{"leaf", {{"default", true}}}, {"children", {{"items", {{"$ref", "#"}}}}}}}});
  const json filled =
      validator.apply_defaults({{"children", {json::object(), {{"children", {json::object()}}}}}});
  EXPECT_EQ(filled["leaf"], true);
  EXPECT_EQ(filled["children"][0]["leaf"], true);
  EXPECT_EQ(filled["children"][1]["children"][0]["leaf"], true);
}

// --------------------------------------------------------- job-like schema

const json& job_schema() {
  static const json schema = json::parse(R"({
    "$schema": "http://json-schema.org/draft-07/schema#",
    "title": "GearSPH job",
    "type": "object",
    "required": ["scene", "time"],
    "additionalProperties": false,
    "properties": {
      "name": {"type": "string", "pattern": "^[A-Za-z0-9_-]+$", "maxLength": 64},
      "scene": {"$ref": "#/definitions/scene", "default": {}},
      "time": {
        "type": "object",
        "additionalProperties": false,
        "required": ["end"],
        "properties": {
          "end": {"type": "number", "exclusiveMinimum": 0},
          "cfl": {"type": "number", "minimum": 0.0001, "maximum": 0.5, "default": 0.3},
          "outputs": {"type": "integer", "minimum": 1, "default": 100}
        }
      },
      "bodies": {
        "type": "array", "minItems": 1,
        "items": {"$ref": "#/definitions/body"}
      },
      "tags": {"type": "array", "items": {"type": "string"}, "uniqueItems": true}
    },
    "definitions": {
      "scene": {
        "type": "object",
        "properties": {
          "type": {"enum": ["plate", "strip_wave", "spinning_disk"], "default": "plate"},
          "resolution": {"type": "number", "exclusiveMinimum": 0, "default": 0.001}
        },
        "if": {"properties": {"type": {"const": "spinning_disk"}}},
        "then": {"properties": {"rpm": {"type": "number", "default": 3000}}, "required": ["rpm"]},
        "else": {"properties": {"thickness": {"type": "number", "default": 0.01}}}
      },
      "body": {
        "type": "object",
        "required": ["material"],
        "properties": {
          "material": {
            "oneOf": [
              {"title": "named material", "type": "string", "enum": ["steel", "aluminium"]},
              {"title": "custom material", "$ref": "#/definitions/material"}
            ]
          },
          "position": {"type": "array", "items": [{"type": "number"}, {"type": "number"}],
                       "additionalItems": false, "minItems": 2}
        }
      },
      "material": {
        "type": "object",
        "additionalProperties": false,
        "required": ["density"],
        "properties": {
          "density": {"type": "number", "exclusiveMinimum": 0},
          "poisson_ratio": {"type": "number", "minimum": 0, "exclusiveMaximum": 0.5, "default": 0.3}
        }
      }
    }
  })");
  return schema;
}

TEST(JsonSchemaJob, ValidJobPassesAndGetsDefaults) {
  const Validator validator(job_schema());
  const json job = json::parse(R"({"time": {"end": 0.01},
                                    "bodies": [{"material": "steel", "position": [0, 1.5]},
                                               {"material": {"density": 2700}}]})");
  const json filled = validator.apply_defaults(job);
  EXPECT_TRUE(validator.validate(filled).empty()) << describe(validator.validate(filled));
  EXPECT_EQ(filled["scene"]["type"], "plate");
  EXPECT_EQ(filled["scene"]["thickness"], 0.01);
  EXPECT_FALSE(filled["scene"].contains("rpm"));
  EXPECT_EQ(filled["time"]["cfl"], 0.3);
  EXPECT_EQ(filled["bodies"][1]["material"]["poisson_ratio"], 0.3);
  EXPECT_FALSE(filled["bodies"][0].contains("poisson_ratio"));

  const json disk =
      validator.apply_defaults({{"scene", {{"type", "spinning_disk"}}}, {"time", {{"end", 1}}}});
  EXPECT_EQ(disk["scene"]["rpm"], 3000);
  EXPECT_FALSE(disk["scene"].contains("thickness"));
}

TEST(JsonSchemaJob, TypicalMistakesGetPreciseMessages) {
  const Validator validator(job_schema());
  const json job = json::parse(R"({
    "nmae": "run 1",
    "scene": {"type": "plat"},
    "time": {"end": 0, "cfl": 0.7, "outputs": 2.5},
    "bodies": [{"material": "stel"}, {"material": {"density": -1, "poison_ratio": 0.3}},
               {"position": [1, "2", 3]}],
    "tags": ["a", "b", "a"]
  })");
  const auto errors = validator.validate(job);
  EXPECT_TRUE(has_error(errors, "/nmae", {"not a known field", "did you mean \"name\"?"}));
  EXPECT_TRUE(has_error(errors, "/scene/type", {"one of", "did you mean \"plate\"?"}));
  EXPECT_TRUE(has_error(errors, "/time/end", {"greater than 0", "got 0"}));
  EXPECT_TRUE(has_error(errors, "/time/cfl", {"at most 0.5", "got 0.7"}));
  EXPECT_TRUE(has_error(errors, "/time/outputs", {"integer", "2.5"}));
  EXPECT_TRUE(has_error(errors, "/bodies/0/material", {"did you mean \"steel\"?"}));
  EXPECT_TRUE(has_error(errors, "/bodies/1/material/density", {"greater than 0"}));
  EXPECT_TRUE(has_error(errors, "/bodies/1/material/poison_ratio",
                        {"not a known field", "did you mean \"poisson_ratio\"?"}));
  EXPECT_TRUE(has_error(errors, "/bodies/2/material", {"is required"}));
  EXPECT_TRUE(has_error(errors, "/bodies/2/position/1", {"must be a number", "\"2\""}));
  EXPECT_TRUE(has_error(errors, "/bodies/2/position", {"at most 2 items"}));
  EXPECT_TRUE(has_error(errors, "/tags/2", {"repeats item 0"}));
  EXPECT_TRUE(std::is_sorted(errors.begin(), errors.end(),
                             [](const Error& a, const Error& b) { return a.pointer < b.pointer; }));
  for (const auto& e : errors) {
    EXPECT_FALSE(contains(e.message, "0.000000")) << e.message;
    EXPECT_EQ(e.message.find('\n'), std::string::npos) << e.message;
  }
}

TEST(JsonSchemaJob, MissingTopLevelMembers) {
  const Validator validator(job_schema());
  const auto errors = validator.validate(json::object());
  ASSERT_EQ(errors.size(), 2u) << describe(errors);
  EXPECT_EQ(errors[0], (Error{"/scene", "is required"}));
  EXPECT_EQ(errors[1], (Error{"/time", "is required"}));
  EXPECT_TRUE(
      has_error(validator.validate(json::array()), "", {"must be an object, not an array"}));
}

// -------------------------------------------------------------- robustness

class RandomJson {
 public:
  explicit RandomJson(unsigned seed) : rng_(seed) {}

  json value(int depth) {
    switch (pick(depth > 6 ? 6 : 8)) {
      case 0:
        return nullptr;
      case 1:
        return pick(2) == 1;
      case 2:
        return integer();
      case 3:
        return real();
      case 4:
      case 5:
        return text();
      case 6:
        return array(depth);
      default:
        return object(depth);
    }
  }

 private:
  int pick(int n) { return std::uniform_int_distribution<int>(0, n - 1)(rng_); }

  json integer() {
    switch (pick(4)) {
      case 0:
        return std::numeric_limits<std::int64_t>::min();
      case 1:
        return std::numeric_limits<std::uint64_t>::max();
      default:
        return std::uniform_int_distribution<std::int64_t>(-1000, 1000)(rng_);
    }
  }

  json real() {
    const double choices[] = {0.0, -0.0, 1e308, -1e308, 4.9e-324, 0.1, 1e-8, 3.0, 2.5e11};
    if (pick(2) == 0) return choices[pick(9)];
    return std::uniform_real_distribution<double>(-1e6, 1e6)(rng_);
  }

  json text() {
    static const std::vector<std::string> pieces = {"plate",
                                                    "strip_wave",
                                                    "spinning_disk",
                                                    "density",
                                                    "a",
                                                    "",
                                                    "~",
                                                    "/",
                                                    "\u00e9",
                                                    "\xF0\x9F\x98\x80",
                                                    "\xff\xfe",
                                                    "\"",
                                                    "\\",
                                                    "\n",
                                                    "type",
                                                    "scene",
                                                    "time",
                                                    "end"};
    std::string s;
    for (int i = pick(4); i > 0; --i) s += pieces[static_cast<std::size_t>(pick(18))];
    if (pick(20) == 0) s += std::string(static_cast<std::size_t>(pick(3000)), 'a');
    return s;
  }

  json array(int depth) {
    json out = json::array();
    for (int i = pick(5); i > 0; --i) out.push_back(value(depth + 1));
    if (pick(30) == 0) out.push_back(nested_arrays(pick(400)));
    return out;
  }

  json object(int depth) {
    json out = json::object();
    for (int i = pick(5); i > 0; --i) out[text().get<std::string>()] = value(depth + 1);
    return out;
  }

  std::mt19937 rng_;
};

TEST(JsonSchemaRobustness, RandomInstancesNeverThrow) {
  const std::vector<json> schemas = {
      job_schema(),
      true,
      {{"type", "array"}, {"items", {{"$ref", "#"}}}, {"uniqueItems", true}},
      {{"anyOf",
        {{{"$ref", "#/definitions/o"}}, {{"type", "array"}, {"items", {{"$ref", "#"}}}}, true}},
       {"definitions",
        {{"o",
          {{"type", "object"},
           {"patternProperties", {{"^[a-z]", {{"$ref", "#"}}}}},
           {"propertyNames", {{"maxLength", 10}}},
           {"additionalProperties", {{"type", "string"}, {"pattern", "^(a|b)*$"}}}}}}}},
      {{"oneOf",
        {{{"multipleOf", 0.1}}, {{"multipleOf", 3}}, {{"minLength", 2}, {"maxLength", 5}}}},
       {"not", {{"const", {1, 2}}}},
       {"contains", {{"enum", {"plate", 3}}}}},
      {{"if", {{"required", {"type"}}}},
       {"then", {{"properties", {{"type", {{"enum", {"plate", "disk"}}, {"default", "plate"}}}}}}},
       {"else", {{"properties", {{"x", {{"default", json::object()}, {"$ref", "#"}}}}}}}},
  };
  RandomJson random(20240601u);
  for (int i = 0; i < 400; ++i) {
    const json instance = random.value(0);
    for (const auto& schema : schemas) {
      const Validator validator(schema);
      std::vector<Error> errors;
      ASSERT_NO_THROW(errors = validator.validate(instance)) << instance.dump();
      ASSERT_NO_THROW(validator.apply_defaults(instance)) << instance.dump();
      EXPECT_LE(errors.size(), 50u);
      for (const auto& e : errors) {
        EXPECT_FALSE(e.message.empty());
        EXPECT_TRUE(e.pointer.empty() || e.pointer[0] == '/') << e.pointer;
      }
    }
  }
}

}  // namespace
