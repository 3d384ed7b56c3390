// POST /rating: synchronous, like /preview: the rating takes microseconds,
// so it is answered on the request, never queued. A document the schema or
// ISO 6336 refuses is a 400 problem with one error per bad field.
#include "server/routes_rating.hpp"

#include "server/problem.hpp"
#include "server/submission.hpp"
#include "solver/gear/iso6336_rating.hpp"

namespace gearsph::server::routes {

namespace {

inline constexpr const char* kInvalidRating = "urn:gearsph:problem:invalid-rating";

StringResponse refused(const Request& req, const gear::iso6336::InvalidRating& e) {
  nlohmann::json list = nlohmann::json::array();
  for (const auto& i : e.issues) list.push_back({{"pointer", i.pointer}, {"detail", i.message}});
  problem::Problem p;
  p.status = http::status::bad_request;
  p.type = kInvalidRating;
  p.title = "Invalid rating";
  p.detail = std::to_string(e.issues.size()) + " field" + (e.issues.size() == 1 ? "" : "s") +
             " of the rating cannot be rated; see errors";
  p.instance = req.path;
  p.extra["errors"] = std::move(list);
  return problem::make(p);
}

}  // namespace

Response rating(Services&, Request& req) {
  auto body = read_json_body(req);
  if (auto* error = std::get_if<StringResponse>(&body)) return std::move(*error);
  try {
    return json_response(http::status::ok,
                         gear::iso6336::rate_document(std::get<nlohmann::json>(body)));
  } catch (const gear::iso6336::InvalidRating& e) {
    return refused(req, e);
  }
}

}  // namespace gearsph::server::routes
