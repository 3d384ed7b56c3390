#pragma once
// The layout of results.h5, shared by the writer, the reader and the XDMF
// sidecar. Paths, units and the per-frame fields live here and nowhere else.
//
// results.h5 (format_version 1):
//   /meta          group; attributes only:
//                    format          "gearsph-results" (identifies our files)
//                    format_version  int64, kFormatVersion
//                    solver_version  text, kSolverVersion
//                    job             text, the job JSON with every default
//                    units           text, JSON object {dataset path: unit}
//                    created         text, ISO 8601 UTC
//                    particles       int64, N
//                    frames_planned  int64, PreparedJob::frames
//                    status          text (16 bytes, rewritten in place):
//                                    running | completed | cancelled | diverged
//                    steps_done      int64, rewritten at the end of the run
//   /bodies        parallel datasets, one row per body (B rows):
//                    name            fixed-length text [B]
//                    particle_range  int64 [B x 2], particle indices [begin, end)
//                    E_Pa, nu, rho_kg_m3   float64 [B]
//   /initial       the reference configuration:
//                    position (float64 [N x 3], z = 0), body_id (int32 [N]),
//                    particle_id (int32 [N]), mass (float64 [N], kg per m of thickness)
//   /frames        snapshots in frame-indexed datasets, F = frames_planned rows
//                  allocated when the run starts (unlimited along axis 0):
//                    time (float64 [F]), step (int64 [F])  -- the commit markers
//                    position, velocity, displacement       float64 [F x N x 3]
//                    stress_xx, stress_yy, stress_xy, stress_zz, pressure,
//                    von_mises, density                     float64 [F x N]
//                    body_id, particle_id                   int32   [F x N]
//                  Chunks of one frame, shuffle + deflate. Frame k is complete
//                  iff step[k] holds a value; rows not written hold the fill
//                  value (NaN, -1 for integers). See results_writer.hpp.
//   /histories     one float64 [R] dataset per History column, in the order
//                  given by the attribute `columns` (first: time_s, the
//                  commit marker of a row); R rows allocated as planned, fill
//                  value NaN; uncompressed 1024-row chunks.
//   /outlines      only if the scene has outlines (outlines.hpp).
//   /cracks        only if the run has cracks: each crack's path in the
//                  reference configuration at the end of the run, as the
//                  outlines are stored (a grown crack: the mouth, the drawn
//                  tip, then one vertex per increment; docs/cracks.md).
//
// The stress fields are the full Cauchy stress sigma = -p I + S (plane
// strain, so sigma_zz != 0); pressure is positive in compression.
#include <array>
#include <string>

namespace gearsph::results {

inline constexpr const char* kFormatName = "gearsph-results";
inline constexpr long kFormatVersion = 1;
// Keep in step with project(... VERSION) in the top-level CMakeLists.txt.
inline constexpr const char* kSolverVersion = "0.1.0";

inline constexpr const char* kResultsFile = "results.h5";
inline constexpr const char* kXdmfFile = "results.xmf";

// One per-particle field of a frame.
struct FieldSpec {
  const char* name;
  int components;  // 3: [N x 3] vector (z = 0); 1: [N] scalar
  bool integer;    // int32 rather than float64
  const char* unit;
};

inline constexpr std::array<FieldSpec, 12> kFrameFields = {{
    {"position", 3, false, "m"},
    {"velocity", 3, false, "m/s"},
    {"displacement", 3, false, "m"},
    {"stress_xx", 1, false, "Pa"},
    {"stress_yy", 1, false, "Pa"},
    {"stress_xy", 1, false, "Pa"},
    {"stress_zz", 1, false, "Pa"},
    {"pressure", 1, false, "Pa"},
    {"von_mises", 1, false, "Pa"},
    {"density", 1, false, "kg/m^3"},
    {"body_id", 1, true, "1"},
    {"particle_id", 1, true, "1"},
}};

inline constexpr const char* kStatusRunning = "running";
inline constexpr std::size_t kStatusBytes = 16;

}  // namespace gearsph::results
