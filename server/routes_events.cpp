// Server-Sent Events: the handler decides where a stream starts (a status
// snapshot, or after the client's Last-Event-ID) and hands the connection
// to the session, which streams from the event hub.
//
// A job's status never goes backwards on its stream: a client that resumes
// gets the events after its last one if the hub still holds them all, and
// otherwise the current status, as the event the hub was at when the
// status was read, and only what came after it.
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
  // The hub's position before the status is read: whatever happens after
  // the read has a later id and is streamed.
  const std::uint64_t now = s.hub.last_id();
  const auto job = is_id(id) ? s.store.job(id) : std::nullopt;
  if (!job) return problem::no_such_job(req);
  EventStream es = start(req, id);
  const bool finished = is_terminal_status(job->status);
  if (es.last_event_id) {
    const EventHub::Resume r = s.hub.resume(*es.last_event_id, id);
    if (r.complete) {
      if (finished && !r.final_status_ahead) {
        // The client has seen the final status: nothing more will come.
        // 204 also tells a browser's EventSource to stop reconnecting.
        StringResponse done{http::status::no_content, 11};
        done.set(http::field::cache_control, "no-cache");
        return done;
      }
      es.after = *es.last_event_id;
      return es;
    }
  }
  Event snapshot;
  snapshot.id = now;
  snapshot.type = "status";
  snapshot.data = s.status_of(*job).dump();
  es.first = sse_text(snapshot);
  es.final = finished;
  es.after = now;
  return es;
}

Response all_events(Services& s, Request& req) {
  EventStream es = start(req, "");
  const std::uint64_t now = s.hub.last_id();
  es.after = now;
  if (es.last_event_id) {
    if (s.hub.resume(*es.last_event_id, "").complete) {
      es.after = *es.last_event_id;
    } else {
      // Events were missed: the client fetches /jobs again.
      es.first = "id: " + std::to_string(now) + "\nevent: reset\ndata: {}\n\n";
    }
  }
  return es;
}

}  // namespace gearsph::server::routes
