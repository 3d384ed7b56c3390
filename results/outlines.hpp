#pragma once
// Scene outlines (tooth profiles, plate edges) in /outlines, for renderers
// and ParaView users who want the geometry as drawn rather than as
// particles. Written only when the scene type has an `outlines` member
// (name, body, points, closed): the template below finds it at compile time.
//
// /outlines: parallel datasets, one row per outline (K rows):
//   name (text [K]), body (int32 [K], -1: none), closed (uint8 [K]),
//   offsets (int64 [K+1]): outline k is points[offsets[k], offsets[k+1]),
//   points (float64 [P x 2], m).
#include <array>
#include <string>
#include <vector>

#include "results/h5_util.hpp"

namespace gearsph::results {

struct StoredOutline {
  std::string name;
  int body = -1;
  std::vector<std::array<double, 2>> points;
  bool closed = false;
};

// `group`: "outlines", or "cracks" for the cracks' paths at the end of a run
// (the same layout; results_layout.hpp).
void write_outlines(hid_t file, const std::vector<StoredOutline>& outlines,
                    const char* group = "outlines");
// Empty if the file has no /outlines; a run's /cracks follow them (named
// "crack", open), so that a renderer draws them over the field.
std::vector<StoredOutline> read_outlines(hid_t file);

template <class SceneT>
void write_scene_outlines(hid_t file, const SceneT& scene) {
  if constexpr (requires { scene.outlines; }) {
    std::vector<StoredOutline> list;
    for (const auto& o : scene.outlines) {
      list.push_back({o.name,
                      static_cast<int>(o.body),
                      {o.points.begin(), o.points.end()},
                      static_cast<bool>(o.closed)});
    }
    if (!list.empty()) write_outlines(file, list);  // no /outlines without outlines
  }
}

}  // namespace gearsph::results
