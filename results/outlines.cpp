#include "results/outlines.hpp"

namespace gearsph::results {

void write_outlines(hid_t file, const std::vector<StoredOutline>& outlines, const char* name) {
  h5::Id group = h5::create_group(file, name);
  const std::size_t k = outlines.size();
  std::vector<std::string> names;
  std::vector<std::int32_t> body;
  std::vector<std::uint8_t> closed;
  std::vector<std::int64_t> offsets{0};
  std::vector<double> points;
  for (const StoredOutline& o : outlines) {
    names.push_back(o.name);
    body.push_back(o.body);
    closed.push_back(o.closed ? 1 : 0);
    for (const auto& p : o.points) points.insert(points.end(), p.begin(), p.end());
    offsets.push_back(static_cast<std::int64_t>(points.size() / 2));
  }
  h5::write_text_dataset(group.get(), "name", names);
  h5::write_dataset(group.get(), "body", body, {k});
  h5::write_dataset(group.get(), "closed", closed, {k});
  h5::write_dataset(group.get(), "offsets", offsets, {k + 1});
  h5::write_dataset(group.get(), "points", points, {points.size() / 2, 2});
}

namespace {

std::vector<StoredOutline> read_group(hid_t file, const char* name) {
  if (!h5::has_link(file, name)) return {};
  h5::Id group = h5::open_group(file, name);
  const hid_t g = group.get();
  const auto names = h5::read_text_dataset(h5::open_dataset(g, "name").get());
  const auto body = h5::read_all<std::int32_t>(h5::open_dataset(g, "body").get());
  const auto closed = h5::read_all<std::uint8_t>(h5::open_dataset(g, "closed").get());
  const auto offsets = h5::read_all<std::int64_t>(h5::open_dataset(g, "offsets").get());
  const auto points = h5::read_all<double>(h5::open_dataset(g, "points").get());
  if (body.size() != names.size() || closed.size() != names.size() ||
      offsets.size() != names.size() + 1 ||
      (!offsets.empty() && static_cast<std::size_t>(offsets.back()) * 2 != points.size())) {
    throw h5::Error("/outlines: datasets of inconsistent lengths");
  }
  std::vector<StoredOutline> out(names.size());
  for (std::size_t k = 0; k < names.size(); ++k) {
    if (offsets[k] < 0 || offsets[k] > offsets[k + 1]) throw h5::Error("/outlines: bad offsets");
    out[k].name = names[k];
    out[k].body = body[k];
    out[k].closed = closed[k] != 0;
    for (auto i = offsets[k]; i < offsets[k + 1]; ++i) {
      out[k].points.push_back({points[2 * i], points[2 * i + 1]});
    }
  }
  return out;
}

}  // namespace

std::vector<StoredOutline> read_outlines(hid_t file) {
  std::vector<StoredOutline> out = read_group(file, "outlines");
  for (StoredOutline& c : read_group(file, "cracks")) out.push_back(std::move(c));
  return out;
}

}  // namespace gearsph::results
