#pragma once
// Makes every run (gearsph run, the job service) write results.h5 and
// results.xmf: registers a ResultsWriter factory with gearsph::register_output.
// Call once at start-up; calling it again has no effect.
namespace gearsph::results {

void register_outputs();

}  // namespace gearsph::results
