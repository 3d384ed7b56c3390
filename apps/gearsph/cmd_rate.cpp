// gearsph rate RATING.json: the ISO 6336 rating of a gear pair
// (schemas/rating.schema.json) printed as JSON; a refused document lists
// each bad field's JSON pointer with a sentence and exits with 2.
#include <cstdio>
#include <stdexcept>

#include "apps/gearsph/cli.hpp"
#include "solver/gear/iso6336_rating.hpp"

namespace gearsph::cli {

int cmd_rate(Args& args) {
  const auto out = args.option("out");
  const auto pos = args.positional();
  if (pos.size() != 1) throw std::invalid_argument("usage: gearsph rate RATING.json [--out FILE]");
  nlohmann::json doc;
  try {
    doc = nlohmann::json::parse(read_file(pos[0]));
  } catch (const nlohmann::json::parse_error& e) {
    std::fprintf(stderr, "gearsph rate: %s: /: is not valid JSON: %s\n", pos[0].c_str(), e.what());
    return 2;
  }
  nlohmann::json verdict;
  try {
    verdict = gear::iso6336::rate_document(doc);
  } catch (const gear::iso6336::InvalidRating& e) {
    std::fprintf(stderr, "gearsph rate: %s: %s\n", pos[0].c_str(), e.what());
    return 2;
  }
  const std::string text = verdict.dump(2) + "\n";
  if (out) {
    std::FILE* f = std::fopen(out->c_str(), "w");
    if (!f) throw std::runtime_error("cannot write " + *out);
    std::fputs(text.c_str(), f);
    std::fclose(f);
  } else {
    std::fputs(text.c_str(), stdout);
  }
  return 0;
}

}  // namespace gearsph::cli
