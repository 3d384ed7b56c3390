#include "results/register_outputs.hpp"

#include <memory>
#include <mutex>

#include "results/results_writer.hpp"
#include "solver/run/execute.hpp"

namespace gearsph::results {

void register_outputs() {
  static std::once_flag once;
  std::call_once(once, [] {
    register_output([](const PreparedJob&, const std::filesystem::path& dir) {
      return std::unique_ptr<RunObserver>(std::make_unique<ResultsWriter>(dir));
    });
  });
}

}  // namespace gearsph::results
