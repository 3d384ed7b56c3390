#include "solver/physics/crack_cut.hpp"

#include <cmath>

namespace gearsph::physics {

namespace {

// The cracks of particle i's body; most bodies have none.
std::vector<geometry::Crack> cracks_of(const std::vector<geometry::Crack>& cracks, int body) {
  std::vector<geometry::Crack> out;
  for (const geometry::Crack& c : cracks) {
    if (c.body == body) out.push_back(c);
  }
  return out;
}

}  // namespace

std::size_t cut_pairs_across_cracks(const Particles& p, const std::vector<geometry::Crack>& cracks,
                                    std::vector<std::uint32_t>& rows,
                                    std::vector<std::uint32_t>& js, std::vector<CutPair>* cut_out) {
  if (cracks.empty() || rows.empty()) return 0;
  std::vector<std::vector<geometry::Crack>> by_body;
  std::size_t out = 0;
  std::uint32_t begin = rows[0];
  for (std::size_t i = 0; i + 1 < rows.size(); ++i) {
    const std::uint32_t end = rows[i + 1];
    const auto body = static_cast<std::size_t>(p.body[i]);
    if (by_body.size() <= body) by_body.resize(body + 1);
    if (by_body[body].empty()) by_body[body] = cracks_of(cracks, static_cast<int>(body));
    for (std::uint32_t k = begin; k < end; ++k) {
      const std::uint32_t j = js[k];
      const geometry::Point a{p.x0[i], p.y0[i]}, b{p.x0[j], p.y0[j]};
      int segment = -1;
      const geometry::Crack* crack = nullptr;
      if (p.body[j] == p.body[i]) {
        for (const geometry::Crack& c : by_body[body]) {
          segment = geometry::crack_segment_cut(c, a, b);
          if (segment >= 0) {
            crack = &c;
            break;
          }
        }
      }
      if (segment < 0) {
        js[out++] = j;
        continue;
      }
      if (cut_out) {
        const auto s = static_cast<std::size_t>(segment);
        const geometry::Point d = crack->path[s + 1] - crack->path[s];
        const double len = std::hypot(d.x, d.y);
        CutPair cp{static_cast<std::uint32_t>(i), j, -d.y / len, d.x / len};
        if ((b.x - a.x) * cp.nx + (b.y - a.y) * cp.ny < 0.0) cp.nx = -cp.nx, cp.ny = -cp.ny;
        cut_out->push_back(cp);
      }
    }
    begin = end;
    rows[i + 1] = static_cast<std::uint32_t>(out);
  }
  const std::size_t removed = js.size() - out;
  js.resize(out);
  js.shrink_to_fit();
  return removed;
}

}  // namespace gearsph::physics
