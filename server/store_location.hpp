#pragma once
// Where the job store is, as an operator names it: `--store`, a file
// (`--store-file`, so that no password shows in the process list) or the
// environment (GEARSPH_STORE). Accepted forms:
//   postgresql://user@host:port/db?...   a libpq connection URI (postgres:// too)
//   host=db.example dbname=gearsph ...   libpq's key=value form, on purpose
//   sqlite:PATH                          an SQLite file
//   PATH                                 an SQLite file (no '=' and no scheme)
// Anything else is refused with a sentence, never taken for a file name.
#include <optional>
#include <string>
#include <vector>

namespace gearsph::server {

enum class StoreEngine { sqlite, postgresql };

struct StoreLocation {
  StoreEngine engine = StoreEngine::sqlite;
  std::string target;  // the SQLite file, or the libpq connection string
};

// Throws std::invalid_argument saying what was expected.
StoreLocation parse_store_location(const std::string& text);

// True if the text carries a password (a URI's user:password@, or password=).
bool store_holds_password(const std::string& text);

// The store named by --store, --store-file or GEARSPH_STORE (`environment`,
// nullptr if unset), in that order; "" if none. At most one of the options;
// a password given on the command line adds a warning.
std::string store_from_options(const std::optional<std::string>& store,
                               const std::optional<std::string>& store_file,
                               const char* environment, std::vector<std::string>& warnings);

}  // namespace gearsph::server
