// The store's location as an operator gives it (server/store_location.hpp):
// the forms accepted, the ones refused with a sentence (a libpq key=value
// string once became an SQLite file of that name), and a password kept out
// of the process list.
#include <gtest/gtest.h>

#include <unistd.h>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "server/store_location.hpp"

namespace gearsph::server {
namespace {

TEST(StoreLocation, AcceptsPostgresUrisKeyValueStringsAndSqliteFiles) {
  const auto uri = parse_store_location("postgresql://gearsph@db.example:5433/gearsph");
  EXPECT_EQ(uri.engine, StoreEngine::postgresql);
  EXPECT_EQ(parse_store_location("postgres://db/x").engine, StoreEngine::postgresql);
  const auto kv = parse_store_location("host=db.example port=5433 dbname=gearsph user=gearsph");
  EXPECT_EQ(kv.engine, StoreEngine::postgresql);
  EXPECT_EQ(kv.target, "host=db.example port=5433 dbname=gearsph user=gearsph");
  const auto file = parse_store_location("sqlite:/var/lib/gearsph/jobs.db");
  EXPECT_EQ(file.engine, StoreEngine::sqlite);
  EXPECT_EQ(file.target, "/var/lib/gearsph/jobs.db");
  EXPECT_EQ(parse_store_location("jobs.db").engine, StoreEngine::sqlite);
}

TEST(StoreLocation, RefusesWhatItCannotTellApart) {
  for (const char* bad : {"mysql://db/x", "", "sqlite:", "dbname gearsph=", "/tmp/a=b.db"}) {
    try {
      parse_store_location(bad);
      ADD_FAILURE() << "accepted '" << bad << "'";
    } catch (const std::invalid_argument& e) {
      EXPECT_GT(std::string(e.what()).size(), 10u) << bad;
    }
  }
  // Where a file name holds '=', the explicit form takes it.
  EXPECT_EQ(parse_store_location("sqlite:/tmp/a=b.db").target, "/tmp/a=b.db");
}

TEST(StoreLocation, APasswordOnTheCommandLineIsWarnedAbout) {
  EXPECT_TRUE(store_holds_password("postgresql://gearsph:secret@db/gearsph"));
  EXPECT_TRUE(store_holds_password("host=db password=secret dbname=gearsph"));
  EXPECT_FALSE(store_holds_password("postgresql://gearsph@db:5432/gearsph"));
  EXPECT_FALSE(store_holds_password("host=db dbname=gearsph"));
  std::vector<std::string> warnings;
  EXPECT_EQ(
      store_from_options(std::string("postgresql://u:pw@db/x"), std::nullopt, nullptr, warnings),
      "postgresql://u:pw@db/x");
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("--store-file"), std::string::npos);
}

TEST(StoreLocation, FromAFileOrTheEnvironment) {
  const auto file = std::filesystem::temp_directory_path() /
                    ("gearsph-store-" + std::to_string(::getpid()) + ".txt");
  std::ofstream(file) << "  postgresql://u:pw@db/x  \n# not read\n";
  std::vector<std::string> warnings;
  EXPECT_EQ(store_from_options(std::nullopt, file.string(), "ignored", warnings),
            "postgresql://u:pw@db/x");
  EXPECT_TRUE(warnings.empty());  // not in the process list
  EXPECT_EQ(store_from_options(std::nullopt, std::nullopt, "sqlite:/x.db", warnings),
            "sqlite:/x.db");
  EXPECT_EQ(store_from_options(std::nullopt, std::nullopt, nullptr, warnings), "");
  EXPECT_THROW(store_from_options(std::string("a"), file.string(), nullptr, warnings),
               std::invalid_argument);
  std::filesystem::remove(file);
  EXPECT_THROW(store_from_options(std::nullopt, file.string(), nullptr, warnings),
               std::invalid_argument);
}

}  // namespace
}  // namespace gearsph::server
