#pragma once
// The wording of schema errors (json_schema.cpp): how values, numbers, lists
// and near misses are said in one English sentence.
#include <cstddef>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace gearsph::jsonschema::wording {

using json = nlohmann::json;

// Values shown in messages are abbreviated beyond this many characters.
inline constexpr std::size_t kShortValue = 40;
// Lists in messages (enum values, known fields) are cut after this many.
inline constexpr std::size_t kMaxListed = 25;

std::size_t count_code_points(const std::string& s);
std::string plural(std::size_t n, const std::string& noun);
// A string in JSON quotes: "\"plate\"".
std::string quote(const std::string& s);
// "a", "a or b", "a, b or c" (or "and").
std::string join_words(const std::vector<std::string>& parts, const std::string& conjunction);
std::string join_or(const std::vector<std::string>& parts);
// Joins with ", ", cutting long lists short ("... and 3 more").
std::string join_listed(const std::vector<std::string>& parts);

// Shortest text that reads back as the same number: "4e-08", "0.353",
// "1000", "1.73e+11"; integers exactly.
std::string format_number(const json& v);
// "a string", "an array", "null", ...
std::string kind_of(const json& v);
// A value as shown after "got": numbers compactly, long strings and
// containers abbreviated ("an array of 3 items").
std::string describe_value(const json& v);
// A required value (const or enum member) as shown after "must be".
std::string expected_value(const json& v);
// " (\"abc\")" after a kind, for values short enough to be worth repeating.
std::string value_suffix(const json& v);

// " — did you mean \"plate\"?" when a candidate is within two edits (case
// and swapped neighbours forgiven, no rewrite of a very short word), else "".
std::string did_you_mean(const std::string& got, const std::vector<std::string>& candidates);

}  // namespace gearsph::jsonschema::wording
