// The official JSON-Schema-Test-Suite, draft-07 (Debian's
// json-schema-test-suite), through jsonschema::Validator: every test of the
// required files passes except those whose schema refers to another document.
// The validator fetches nothing (a job schema is compiled in and whole), so
// those schemas are refused at construction; the list of them is fixed here,
// and any other refusal or wrong answer fails.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "solver/core/json_schema.hpp"

namespace {

using gearsph::jsonschema::Validator;
using nlohmann::json;

// (file, group): schemas that name another document.
const std::set<std::pair<std::string, std::string>> kOtherDocuments = {
    // the draft-07 meta-schema, by its URI
    {"definitions.json", "valid definition"},
    {"definitions.json", "invalid definition"},
    {"ref.json", "remote ref, containing refs itself"},
    // subschemas named by "$id" URIs on a test server
    {"ref.json", "Recursive references between schemas"},
    {"refRemote.json", "remote ref"},
    {"refRemote.json", "fragment within remote ref"},
    {"refRemote.json", "ref within remote ref"},
    {"refRemote.json", "base URI change"},
    {"refRemote.json", "base URI change - change folder"},
    {"refRemote.json", "base URI change - change folder in subschema"},
    {"refRemote.json", "root ref in remote ref"},
};

std::vector<std::filesystem::path> draft7_files() {
  std::vector<std::filesystem::path> files;
  const std::filesystem::path dir = std::filesystem::path(GEARSPH_SCHEMA_SUITE_DIR) / "draft7";
  if (!std::filesystem::is_directory(dir)) return files;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().extension() == ".json") files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

TEST(JsonSchemaSuite, Draft07) {
  const auto files = draft7_files();
  ASSERT_FALSE(files.empty()) << "no suite under " << GEARSPH_SCHEMA_SUITE_DIR
                              << " (scripts/setup.sh installs json-schema-test-suite)";
  int total = 0, passed = 0, skipped = 0;
  std::set<std::pair<std::string, std::string>> refused;
  for (const auto& path : files) {
    const std::string file = path.filename().string();
    std::ifstream in(path);
    for (const json& group : json::parse(in)) {
      const std::string name = group.at("description").get<std::string>();
      const json& tests = group.at("tests");
      total += static_cast<int>(tests.size());
      std::optional<Validator> validator;
      try {
        validator.emplace(group.at("schema"));
      } catch (const std::invalid_argument& e) {
        refused.emplace(file, name);
        skipped += static_cast<int>(tests.size());
        EXPECT_TRUE(kOtherDocuments.count({file, name}))
            << file << " / " << name << ": " << e.what();
        continue;
      }
      for (const json& test : tests) {
        const bool valid = validator->validate(test.at("data")).empty();
        if (valid == test.at("valid").get<bool>()) {
          ++passed;
        } else {
          ADD_FAILURE() << file << " / " << name << " / "
                        << test.at("description").get<std::string>() << ": expected "
                        << (valid ? "invalid" : "valid");
        }
      }
    }
  }
  std::cout << "JSON-Schema-Test-Suite draft-07: " << passed << " of " << total << " passed, "
            << skipped << " skipped (schemas that refer to other documents)\n";
  EXPECT_EQ(refused, kOtherDocuments);
  EXPECT_EQ(passed + skipped, total);
}

}  // namespace
