// The rack's body as modelled: its back is the job's (two modules unless
// given), all of it deformable, with the guided layer that carries the load
// below it. The layer used to lie inside the back, so the deformable back
// was two modules less a kernel support (5 mm of 8 at the default 1 mm
// bulk): the rack read stiffer than the finite-element rack it is checked
// against, and by less the finer the bulk (docs/gears.md, "The rack's
// guided layer").
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>

#include "solver/job/job.hpp"

namespace gearsph {
namespace {

nlohmann::json rack_pinion(const nlohmann::json& discretization) {
  return {{"scene", {{"type", "rack_pinion"}}}, {"discretization", discretization}};
}

TEST(RackBody, TheGuidedLayerLiesBelowTheWholeDeformableBack) {
  for (const nlohmann::json& d : {nlohmann::json::object(), nlohmann::json{{"spacing_m", 0.5e-3}},
                                  nlohmann::json{{"particles", "lattice"}}}) {
    const PreparedJob job = prepare_job(rack_pinion(d), 1);
    const Scene& scene = job.scene;
    const nlohmann::json& rack = scene.description.at("rack");
    const double back = rack.at("back_thickness_m").get<double>();
    const double layer = rack.at("guided_layer_m").get<double>();
    EXPECT_DOUBLE_EQ(back, 8e-3) << d;  // two modules
    EXPECT_GT(layer, 0.0) << d;

    // The outline's flat bottom, and its root line: the lowest point of the
    // tooth spaces, where the segment's cut sides end.
    const Outline& outline = scene.outlines.at(1);
    double bottom = std::numeric_limits<double>::infinity();
    for (const auto& q : outline.points) bottom = std::min(bottom, q[1]);
    double root_line = std::numeric_limits<double>::infinity();
    for (const auto& q : outline.points) {
      if (q[1] > bottom + 1e-9) root_line = std::min(root_line, q[1]);
    }
    EXPECT_NEAR(root_line - bottom, layer + back, 1e-9) << d;

    // Guided particles fill the layer and nothing above it.
    const Simulation& sim = scene.sim;
    const Body& body = sim.bodies.at(1);
    double highest_guided = -std::numeric_limits<double>::infinity();
    std::size_t guided = 0;
    for (std::size_t i = body.begin; i < body.end; ++i) {
      if (sim.particles.motion[i] != 2) continue;
      ++guided;
      highest_guided = std::max(highest_guided, sim.particles.y[i]);
    }
    EXPECT_GT(guided, 0u) << d;
    EXPECT_LT(highest_guided, bottom + layer) << d;
  }
}

}  // namespace
}  // namespace gearsph
