#include "apps/gearsph/cli.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace gearsph::cli {

Args::Args(int argc, char** argv, int first) {
  for (int i = first; i < argc; ++i) args_.emplace_back(argv[i]);
}

std::optional<std::string> Args::option(const std::string& name) {
  for (std::size_t i = 0; i < args_.size(); ++i) {
    if (args_[i] == "--" + name) {
      if (i + 1 >= args_.size()) throw std::invalid_argument("--" + name + " needs a value");
      std::string v = args_[i + 1];
      args_.erase(args_.begin() + static_cast<long>(i), args_.begin() + static_cast<long>(i) + 2);
      return v;
    }
    const std::string prefix = "--" + name + "=";
    if (args_[i].rfind(prefix, 0) == 0) {
      std::string v = args_[i].substr(prefix.size());
      args_.erase(args_.begin() + static_cast<long>(i));
      return v;
    }
  }
  return std::nullopt;
}

bool Args::flag(const std::string& name) {
  for (std::size_t i = 0; i < args_.size(); ++i) {
    if (args_[i] == "--" + name) {
      args_.erase(args_.begin() + static_cast<long>(i));
      return true;
    }
  }
  return false;
}

double Args::seconds(const std::string& name, double fallback, const SecondsRange& range) {
  const auto v = option(name);
  if (!v) return fallback;
  try {
    std::size_t used = 0;
    const double s = std::stod(*v, &used);
    const bool above_lo = range.lo_open ? s > range.lo : s >= range.lo;
    if (used == v->size() && above_lo && s <= range.hi) return s;
  } catch (const std::exception&) {
  }
  throw std::invalid_argument("--" + name + " takes seconds (" + range.allowed + "), not '" + *v +
                              "'");
}

double Args::grace_seconds(const std::string& name) {
  return seconds(name, 0.0, SecondsRange{});
}

int Args::integer(const std::string& name, int fallback) {
  const auto v = option(name);
  if (!v) return fallback;
  try {
    std::size_t used = 0;
    const int n = std::stoi(*v, &used);
    if (used != v->size()) throw std::invalid_argument("");
    return n;
  } catch (const std::exception&) {
    throw std::invalid_argument("--" + name + " takes a whole number, not '" + *v + "'");
  }
}

std::vector<std::string> Args::positional() const {
  for (const std::string& a : args_) {
    if (a.rfind("--", 0) == 0) throw std::invalid_argument("unknown option " + a);
  }
  return args_;
}

std::string Args::positional_first() const {
  return !args_.empty() && args_[0].rfind("--", 0) != 0 ? args_[0] : std::string();
}

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace gearsph::cli
