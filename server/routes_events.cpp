// Server-Sent Events: the handler only checks the request and hands the
// connection to the session, which streams from the event hub.
#include <charconv>

#include "server/problem.hpp"
#include "server/routes.hpp"

namespace gearsph::server::routes {

namespace {

EventStream start(const Request& req, std::string job_id) {
  EventStream es;
  es.head = http::response<http::empty_body>{http::status::ok, 11};
  es.head.set(http::field::content_type, "text/event-stream");
  es.head.set(http::field::cache_control, "no-cache");
  es.head.set("X-Accel-Buffering", "no");  // reverse proxies: do not hold events back
  es.job_id = std::move(job_id);
  const std::string last = std::string(req.msg["Last-Event-ID"]);
  std::uint64_t id = 0;
  const auto [end, ec] = std::from_chars(last.data(), last.data() + last.size(), id);
  if (!last.empty() && ec == std::errc() && end == last.data() + last.size()) es.last_event_id = id;
  return es;
}

}  // namespace

Response job_events(Services& s, Request& req) {
  const std::string& id = req.param("id");
  if (!is_id(id) || !s.store.job(id)) {
    problem::Problem p;
    p.status = http::status::not_found;
    p.type = problem::kNoSuchJob;
    p.title = "No such job";
    p.detail = "there is no job " + id;
    p.instance = req.path;
    return problem::make(p);
  }
  return start(req, id);
}

Response all_events(Services&, Request& req) {
  return start(req, "");
}

}  // namespace gearsph::server::routes
