#pragma once
// Progress of a job's set-up (scene, particle relaxation, pairs, stable
// step), for set-ups long enough to be worth a word. Whoever prepares a job
// installs a sink for its thread (SetupProgressScope); the set-up's long
// stages call setup_progress(), which reaches the sink only once the
// set-up has taken a second (kSetupQuietS) and then at each new stage and
// at most four times a second within one, so a quick set-up says nothing.
// A thread without a sink (an OpenMP worker, a test) reports to nobody.
#include <functional>
#include <memory>
#include <string>

namespace gearsph {

struct SetupStatus {
  std::string stage;       // e.g. "relaxing particles"
  double fraction = 0.0;   // of this stage, 0..1 (relaxation: of its most iterations)
  double elapsed_s = 0.0;  // since the set-up began
};
using SetupSink = std::function<void(const SetupStatus&)>;

inline constexpr double kSetupQuietS = 1.0;
inline constexpr double kSetupReportEveryS = 0.25;

// Installs `sink` for this thread's set-ups until destroyed (scopes nest:
// the previous sink comes back); it hears nothing for the first `quiet_s`.
class SetupProgressScope {
 public:
  explicit SetupProgressScope(SetupSink sink, double quiet_s = kSetupQuietS);
  ~SetupProgressScope();
  SetupProgressScope(const SetupProgressScope&) = delete;
  SetupProgressScope& operator=(const SetupProgressScope&) = delete;

 private:
  struct Saved;
  std::unique_ptr<Saved> saved_;
};

// Called by set-up stages; cheap when no sink listens.
void setup_progress(const char* stage, double fraction);

}  // namespace gearsph
