#pragma once
// A scene: the particles and constraints of one job, plus what the scene
// itself knows how to measure (its history columns and its analysis, e.g.
// the plate's period against the thin-plate formula).
#include <array>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "solver/diagnostics/history.hpp"
#include "solver/physics/simulation.hpp"

namespace gearsph {

struct HistoryColumn {
  std::string name;  // with unit suffix, e.g. tip_y_m
  std::function<double(const Simulation&)> value;
};

// A drawn outline of a body in its reference configuration (tooth profiles,
// plate edges), for renderers and ParaView users.
struct Outline {
  std::string name;
  int body = -1;
  std::vector<std::array<double, 2>> points;  // [m]
  bool closed = true;
  // Contact through one side alone: where not zero, only the outline's parts
  // whose outward normal does not point against this direction are contact
  // surfaces (a static check's rack, whose reverse flanks carry nothing:
  // scenes/rack_pinion.cpp, rack_contact_side).
  std::array<double, 2> contact_side{0.0, 0.0};
};

struct Scene {
  Simulation sim;
  std::string type;
  std::vector<HistoryColumn> columns;
  // Case-specific results from the finished (or stopped) run.
  std::function<nlohmann::json(const History&, const Simulation&)> analyse;
  // Scene defaults used when the job leaves them open.
  double default_end_s = 0.0;
  // Surface smoothing of the contact (physics/contact_smoothing.hpp), in
  // spacings, when the job does not set /method/contact/smoothing_spacings:
  // a scene whose contact the particles resolve (hertz) sets 0.
  double contact_smoothing_spacings = 4.0;
  double default_dt_s = 0.0;  // 0: the automatic step (a fraction of the stable limit)
  // The analysis reads times and peaks off the history at the step's
  // resolution (an impact's contact time, a pulse's arrival): a job that
  // names no output.history_points then samples every step, not by time.
  bool history_every_step = false;
  std::vector<Outline> outlines;
  // What was modelled, for the summary (counts, dimensions, notes).
  nlohmann::json description = nlohmann::json::object();
  // Quasi-static stages (a growing crack, docs/cracks.md): called when the
  // run's steps are done, on the state they reached. It may change the
  // model (a longer crack; it then clears sim.reference, so that the run's
  // set-up builds the pairs again on the same particles, displaced as they
  // are) and returns how long to run on [s]; 0 ends the run.
  std::function<double(Simulation&)> next_stage;
  // Ends the run before its last step once it holds what it was run for (a
  // loaded dynamic rack_pinion run's steady mesh: /scene/steady_mesh_periods,
  // docs/dynamics.md). Asked after each history sample; a sentence for the
  // summary's `ended_early`, or empty to go on.
  std::function<std::string(const History&)> ends_early;
};

// A job that is valid against the schema but cannot be built as asked
// (e.g. a spacing that leaves fewer than two particles across a plate).
class JobError : public std::runtime_error {
 public:
  JobError(std::string json_pointer, const std::string& message)
      : std::runtime_error(message), pointer(std::move(json_pointer)) {}
  std::string pointer;
};

}  // namespace gearsph
