#include "server/store_location.hpp"

#include <cctype>
#include <fstream>
#include <regex>
#include <stdexcept>

namespace gearsph::server {

namespace {

bool starts_with(const std::string& s, const char* prefix) {
  return s.rfind(prefix, 0) == 0;
}

// libpq's key=value form: a keyword, then '=' (libpq: "Connection Strings").
bool keyword_value(const std::string& s) {
  static const std::regex form(R"(^\s*[A-Za-z_]+\s*=)");
  return std::regex_search(s, form);
}

std::string trimmed(std::string s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.pop_back();
  std::size_t first = 0;
  while (first < s.size() && std::isspace(static_cast<unsigned char>(s[first]))) ++first;
  return s.substr(first);
}

}  // namespace

StoreLocation parse_store_location(const std::string& text) {
  if (text.empty()) throw std::invalid_argument("the store location is empty");
  if (starts_with(text, "postgresql://") || starts_with(text, "postgres://")) {
    return {StoreEngine::postgresql, text};
  }
  if (starts_with(text, "sqlite:")) {
    const std::string file = text.substr(7);
    if (file.empty()) throw std::invalid_argument("sqlite: names no file (sqlite:PATH)");
    return {StoreEngine::sqlite, file};
  }
  if (keyword_value(text)) return {StoreEngine::postgresql, text};
  static const std::regex scheme(R"(^[A-Za-z][A-Za-z0-9+.-]*://)");
  if (std::regex_search(text, scheme) || text.find('=') != std::string::npos) {
    throw std::invalid_argument(
        "'" + text.substr(0, text.find_first_of("=:")) +
        "...' is not a store GearSPH knows: give postgresql://user@host:port/db, libpq's "
        "key=value form (host=... dbname=...), or sqlite:PATH");
  }
  return {StoreEngine::sqlite, text};
}

bool store_holds_password(const std::string& text) {
  static const std::regex uri(R"(^[A-Za-z][A-Za-z0-9+.-]*://[^/@]*:[^/@]*@)");
  static const std::regex keyword(R"((^|\s)password\s*=)");
  return std::regex_search(text, uri) || std::regex_search(text, keyword);
}

std::string store_from_options(const std::optional<std::string>& store,
                               const std::optional<std::string>& store_file,
                               const char* environment, std::vector<std::string>& warnings) {
  if (store && store_file) throw std::invalid_argument("give --store or --store-file, not both");
  if (store) {
    if (store_holds_password(*store)) {
      warnings.push_back(
          "the --store location holds a password, which every user of this machine can read in "
          "the process list; give it in a file (--store-file, mode 600), in GEARSPH_STORE, or "
          "leave it to libpq's ~/.pgpass (PGPASSFILE)");
    }
    return *store;
  }
  if (store_file) {
    std::ifstream in(*store_file);
    if (!in) throw std::invalid_argument("--store-file " + *store_file + " cannot be read");
    std::string line;
    std::getline(in, line);
    line = trimmed(line);
    if (line.empty()) {
      throw std::invalid_argument("--store-file " + *store_file + " holds no store location");
    }
    return line;
  }
  if (environment && *environment) return trimmed(environment);
  return {};
}

}  // namespace gearsph::server
