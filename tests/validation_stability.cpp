// The fast cells of the stability study (docs/stability.md), re-run: each
// expected failure actually fails (caught by a named detector or criterion)
// and each fix actually holds; where a fix measurably does not, the cell
// documents it and the test holds it to that. The same cells as `gearsph study stability`; the
// oscillating-plate rows take minutes and stay with the command.
#include <gtest/gtest.h>

#include <cctype>
#include <ostream>
#include <set>
#include <string>

#include "solver/study/stability_matrix.hpp"

namespace gearsph {
namespace study {
// gtest names the parameter in failure messages.
void PrintTo(const Cell& c, std::ostream* os) {
  *os << c.case_id << " / " << c.method_id;
}
}  // namespace study

namespace {

using study::Cell;

// Rows that run in seconds (hundreds of particles, about a thousand steps).
bool fast(const Cell& c) {
  static const std::set<std::string> rows = {"tension_strip", "bar_impact", "time_step",
                                             "spinning_disk"};
  return rows.count(c.case_id) > 0;
}

std::vector<Cell> fast_cells() {
  std::vector<Cell> out;
  for (Cell& c : study::stability_cells(false)) {
    if (fast(c)) out.push_back(std::move(c));
  }
  return out;
}

class StabilityCell : public ::testing::TestWithParam<Cell> {};

TEST_P(StabilityCell, OutcomeAsExpected) {
  const Cell& cell = GetParam();
  const study::CellRun run = study::run_cell(cell, 1);
  const study::CellResult& r = run.result;
  // As measured and documented; where that differs from the literature's
  // expectation the cell says why (Cell::deviation).
  EXPECT_TRUE(r.as_documented) << cell.case_id << " / " << cell.method_id << ": documented "
                               << cell.documented << ", got " << r.outcome << " (" << r.failed_by
                               << ") " << r.message;
  EXPECT_EQ(r.as_expected, cell.deviation.empty());
  if (cell.documented == "fails") {
    // A failure is caught by a named detector with a time, never missed.
    EXPECT_FALSE(r.failed_by.empty());
    EXPECT_FALSE(r.message.empty());
  } else {
    EXPECT_EQ(r.steps, r.steps_planned) << r.message;
  }
}

std::string name(const ::testing::TestParamInfo<Cell>& info) {
  std::string s = info.param.case_id + "_" + info.param.method_id;
  for (char& c : s) {
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  }
  return s;
}

INSTANTIATE_TEST_SUITE_P(Fast, StabilityCell, ::testing::ValuesIn(fast_cells()), name);

// The gear rows (full matrix) shortened to 0.2 ms: the wedge of the
// centre-reach contact laws builds from the first steps, and the surface
// contact stays under the elastic impact bound.
TEST(StabilityGear, CentreReachContactWedgesSurfaceContactDoesNot) {
  for (Cell cell : study::stability_cells(true)) {
    if (cell.case_id != "gear_3x_speed") continue;
    cell.job["time"]["end_s"] = 2e-4;
    const study::CellResult r = study::run_cell(cell, 1).result;
    ASSERT_TRUE(r.contact_force_over_bound) << cell.method_id;
    if (cell.method_id == "tl_surface_penalty") {
      EXPECT_NE(r.outcome, "failed") << r.message;
      EXPECT_LT(*r.contact_force_over_bound, 1.0);
    } else {
      EXPECT_EQ(r.failed_by, "wedged") << cell.method_id << ": " << r.message;
    }
  }
}

}  // namespace
}  // namespace gearsph
