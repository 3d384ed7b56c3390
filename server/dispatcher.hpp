#pragma once
// What the HTTP side asks of whatever runs the jobs: the server's own worker
// pool, or an outside scheduler (Slurm). Handlers only wake it, ask for a
// running job's newest progress and stop a dismissed job.
#include <optional>
#include <string>

#include "server/job_store.hpp"

namespace gearsph::server {

class Dispatcher {
 public:
  virtual ~Dispatcher() = default;
  virtual void start() = 0;
  // A job was queued: look for work now rather than at the next poll.
  virtual void notify() = 0;
  // Takes no new jobs; those running go on (a warm shutdown's first part).
  virtual void drain() {}
  // Graceful stop; returns when nothing runs on its behalf any more.
  virtual void stop() = 0;
  // The newest progress of a job running here (in this process's memory),
  // both stages counted.
  virtual std::optional<ProgressUpdate> live(const std::string& id) const = 0;
  // Stops a dismissed job; false if it does not run here.
  virtual bool cancel(const std::string& id) = 0;
  // Jobs running in this process.
  virtual int running() const = 0;
};

}  // namespace gearsph::server
