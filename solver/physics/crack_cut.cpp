#include "solver/physics/crack_cut.hpp"

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
                                    std::vector<std::uint32_t>& js) {
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
      const bool cut =
          p.body[j] == p.body[i] &&
          geometry::any_crack_cuts(by_body[body], {p.x0[i], p.y0[i]}, {p.x0[j], p.y0[j]});
      if (!cut) js[out++] = j;
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
