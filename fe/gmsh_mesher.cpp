#include "fe/gmsh_mesher.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <unordered_map>

namespace gearsph::fe {

namespace {

std::string num(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

double curve_length(const Curve& c) {
  if (c.kind == Curve::Kind::Arc) {
    const Point a = c.points.front() - c.centre, b = c.points.back() - c.centre;
    return geometry::norm(a) * std::abs(std::atan2(geometry::cross(a, b), geometry::dot(a, b)));
  }
  double length = 0.0;
  for (std::size_t i = 1; i < c.points.size(); ++i) {
    length += geometry::norm(c.points[i] - c.points[i - 1]);
  }
  return length;
}

void check_spec(const MeshSpec& spec) {
  if (spec.loops.empty()) throw std::invalid_argument("mesh: no boundary");
  if (!(spec.size_max > 0.0)) throw std::invalid_argument("mesh: size_max must be positive");
  for (const CurveLoop& loop : spec.loops) {
    if (loop.empty()) throw std::invalid_argument("mesh: an empty curve loop");
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const Curve& c = loop[i];
      if (c.points.size() < 2 || (c.kind != Curve::Kind::Spline && c.points.size() != 2)) {
        throw std::invalid_argument("mesh: a line or arc has two points, a spline at least two");
      }
      const Point end = c.points.back(), next = loop[(i + 1) % loop.size()].points.front();
      if (end.x != next.x || end.y != next.y) {
        throw std::invalid_argument("mesh: a curve loop is not closed");
      }
    }
  }
  for (const SizeZone& z : spec.zones) {
    if (!(z.size_min > 0.0 && z.size_max >= z.size_min && z.dist_max > z.dist_min &&
          z.dist_min >= 0.0)) {
      throw std::invalid_argument(
          "mesh: a size zone needs 0 < size_min <= size_max and "
          "0 <= dist_min < dist_max");
    }
    for (const auto& [l, c] : z.curves) {
      if (l < 0 || static_cast<std::size_t>(l) >= spec.loops.size() || c < 0 ||
          static_cast<std::size_t>(c) >= spec.loops[static_cast<std::size_t>(l)].size()) {
        throw std::invalid_argument("mesh: a size zone names a curve that does not exist");
      }
    }
  }
}

}  // namespace

std::string gmsh_geo(const MeshSpec& spec) {
  check_spec(spec);
  std::ostringstream geo;
  geo << "// Written by gearsph (fe/gmsh_mesher.cpp). Lengths in metres.\n"
      << "Mesh.ElementOrder = 2;\n"
      << "Mesh.SecondOrderLinear = 0;  // mid-side nodes on the curves\n"
      << "Mesh.HighOrderOptimize = 0;\n"
      << "Mesh.Algorithm = 6;  // Frontal-Delaunay\n"
      << "Mesh.MeshSizeFromPoints = 0;\n"
      << "Mesh.MeshSizeFromCurvature = 0;\n"
      << "Mesh.MeshSizeExtendFromBoundary = 0;\n"
      << "Mesh.MeshSizeMax = " << num(spec.size_max) << ";\n"
      << "Mesh.MshFileVersion = 2.2;\n"
      << "Mesh.Binary = 0;\n"
      << "General.NumThreads = 1;\n";
  // Points, shared by the curves that meet there (compared exactly).
  std::map<std::pair<double, double>, int> point_ids;
  int next_point = 1;
  auto point = [&](Point p) {
    const auto key = std::make_pair(p.x, p.y);
    const auto it = point_ids.find(key);
    if (it != point_ids.end()) return it->second;
    const int id = next_point++;
    point_ids[key] = id;
    geo << "Point(" << id << ") = {" << num(p.x) << ", " << num(p.y) << ", 0};\n";
    return id;
  };
  int next_curve = 1;
  std::vector<std::vector<int>> curve_ids(spec.loops.size());
  std::map<std::string, std::vector<int>> groups;
  for (std::size_t l = 0; l < spec.loops.size(); ++l) {
    for (const Curve& c : spec.loops[l]) {
      const int id = next_curve++;
      curve_ids[l].push_back(id);
      if (!c.group.empty()) groups[c.group].push_back(id);
      std::vector<int> ids;
      if (c.kind == Curve::Kind::Arc) {
        const int a = point(c.points.front()), centre = point(c.centre), b = point(c.points.back());
        geo << "Circle(" << id << ") = {" << a << ", " << centre << ", " << b << "};\n";
        continue;
      }
      for (const Point& p : c.points) ids.push_back(point(p));
      geo << (c.kind == Curve::Kind::Line ? "Line(" : "Spline(") << id << ") = {";
      for (std::size_t k = 0; k < ids.size(); ++k) geo << (k ? ", " : "") << ids[k];
      geo << "};\n";
    }
  }
  for (std::size_t l = 0; l < spec.loops.size(); ++l) {
    geo << "Curve Loop(" << l + 1 << ") = {";
    for (std::size_t k = 0; k < curve_ids[l].size(); ++k) geo << (k ? ", " : "") << curve_ids[l][k];
    geo << "};\n";
  }
  geo << "Plane Surface(1) = {";
  for (std::size_t l = 0; l < spec.loops.size(); ++l) geo << (l ? ", " : "") << l + 1;
  geo << "};\n";
  geo << "Physical Surface(\"body\") = {1};\n";
  for (const auto& [name, ids] : groups) {
    geo << "Physical Curve(\"" << name << "\") = {";
    for (std::size_t k = 0; k < ids.size(); ++k) geo << (k ? ", " : "") << ids[k];
    geo << "};\n";
  }
  // Size fields: distance to the zone's curves and points, then a threshold.
  std::vector<int> thresholds;
  int field = 1;
  for (const SizeZone& z : spec.zones) {
    // Distance samples every curve at a quarter of the finest size.
    double longest = 0.0;
    for (const auto& [l, c] : z.curves) {
      longest = std::max(
          longest,
          curve_length(spec.loops[static_cast<std::size_t>(l)][static_cast<std::size_t>(c)]));
    }
    const int samples =
        std::clamp(static_cast<int>(std::ceil(4.0 * longest / z.size_min)) + 1, 20, 20000);
    std::vector<int> point_list;
    for (const Point& p : z.points) {
      const int id = next_point++;  // free points: in no curve, only measured from
      geo << "Point(" << id << ") = {" << num(p.x) << ", " << num(p.y) << ", 0};\n";
      point_list.push_back(id);
    }
    const int distance = field++;
    geo << "Field[" << distance << "] = Distance;\n";
    if (!z.curves.empty()) {
      geo << "Field[" << distance << "].CurvesList = {";
      for (std::size_t k = 0; k < z.curves.size(); ++k) {
        geo << (k ? ", " : "")
            << curve_ids[static_cast<std::size_t>(z.curves[k].first)]
                        [static_cast<std::size_t>(z.curves[k].second)];
      }
      geo << "};\n";
      geo << "Field[" << distance << "].NumPointsPerCurve = " << samples << ";\n";
    }
    if (!point_list.empty()) {
      geo << "Field[" << distance << "].PointsList = {";
      for (std::size_t k = 0; k < point_list.size(); ++k) geo << (k ? ", " : "") << point_list[k];
      geo << "};\n";
    }
    const int threshold = field++;
    geo << "Field[" << threshold << "] = Threshold;\n"
        << "Field[" << threshold << "].InField = " << distance << ";\n"
        << "Field[" << threshold << "].SizeMin = " << num(z.size_min) << ";\n"
        << "Field[" << threshold << "].SizeMax = " << num(z.size_max) << ";\n"
        << "Field[" << threshold << "].DistMin = " << num(z.dist_min) << ";\n"
        << "Field[" << threshold << "].DistMax = " << num(z.dist_max) << ";\n";
    thresholds.push_back(threshold);
  }
  if (!thresholds.empty()) {
    const int min_field = field++;
    geo << "Field[" << min_field << "] = Min;\n"
        << "Field[" << min_field << "].FieldsList = {";
    for (std::size_t k = 0; k < thresholds.size(); ++k) geo << (k ? ", " : "") << thresholds[k];
    geo << "};\n"
        << "Background Field = " << min_field << ";\n";
  }
  return geo.str();
}

TriMesh read_msh22(const std::string& text) {
  std::istringstream in(text);
  std::string line;
  std::map<int, std::string> physical_names;
  std::unordered_map<long, Point> gmsh_nodes;
  std::vector<long> node_order;
  struct RawElement {
    int type;
    int physical;
    std::vector<long> nodes;
  };
  std::vector<RawElement> raw;
  bool format_ok = false;
  auto fail = [](const std::string& why) -> void {
    throw std::runtime_error("gmsh mesh file: " + why);
  };
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line == "$MeshFormat") {
      std::getline(in, line);
      format_ok = line.rfind("2.2 0", 0) == 0;
      if (!format_ok) fail("expected ASCII format 2.2, found '" + line + "'");
    } else if (line == "$PhysicalNames") {
      int n = 0;
      in >> n;
      for (int i = 0; i < n; ++i) {
        int dim = 0, tag = 0;
        std::string name;
        in >> dim >> tag;
        std::getline(in, name);
        const auto q0 = name.find('"'), q1 = name.rfind('"');
        if (q0 == std::string::npos || q1 <= q0) fail("malformed physical name");
        physical_names[tag] = name.substr(q0 + 1, q1 - q0 - 1);
      }
    } else if (line == "$Nodes") {
      long n = 0;
      in >> n;
      node_order.reserve(static_cast<std::size_t>(std::max(0L, n)));
      for (long i = 0; i < n; ++i) {
        long id = 0;
        double x = 0, y = 0, z = 0;
        if (!(in >> id >> x >> y >> z)) fail("truncated node list");
        gmsh_nodes[id] = {x, y};
        node_order.push_back(id);
      }
    } else if (line == "$Elements") {
      long n = 0;
      in >> n;
      std::getline(in, line);
      for (long i = 0; i < n; ++i) {
        if (!std::getline(in, line)) fail("truncated element list");
        std::istringstream row(line);
        long id = 0;
        int type = 0, ntags = 0;
        row >> id >> type >> ntags;
        std::vector<int> tags(static_cast<std::size_t>(std::max(0, ntags)));
        for (int& t : tags) row >> t;
        RawElement e{type, tags.empty() ? 0 : tags[0], {}};
        long v = 0;
        while (row >> v) e.nodes.push_back(v);
        raw.push_back(std::move(e));
      }
    }
  }
  if (!format_ok) fail("no $MeshFormat section");
  // gmsh types: 9 = six-node triangle, 8 = three-node line, 2 = linear triangle.
  std::unordered_map<long, int> index;
  std::vector<long> used;
  for (const RawElement& e : raw) {
    if (e.type == 2) fail("linear triangles: the mesh is not second order");
    if (e.type != 9) continue;
    if (e.nodes.size() != 6) fail("a six-node triangle without six nodes");
    for (long v : e.nodes) {
      if (!gmsh_nodes.count(v)) fail("an element names a node that is not listed");
      used.push_back(v);
    }
  }
  if (used.empty()) fail("no six-node triangles");
  std::sort(used.begin(), used.end());
  used.erase(std::unique(used.begin(), used.end()), used.end());
  TriMesh mesh;
  for (long id : node_order) {
    if (std::binary_search(used.begin(), used.end(), id)) {
      index[id] = static_cast<int>(mesh.nodes.size());
      mesh.nodes.push_back(gmsh_nodes[id]);
    }
  }
  for (const RawElement& e : raw) {
    if (e.type == 9) {
      std::array<int, 6> el{};
      for (int k = 0; k < 6; ++k)
        el[static_cast<std::size_t>(k)] = index.at(e.nodes[static_cast<std::size_t>(k)]);
      const Point a = mesh.nodes[el[0]], b = mesh.nodes[el[1]], c = mesh.nodes[el[2]];
      if (geometry::cross(b - a, c - a) < 0.0) el = {el[0], el[2], el[1], el[5], el[4], el[3]};
      mesh.elements.push_back(el);
    } else if (e.type == 8) {
      const auto name = physical_names.find(e.physical);
      if (name == physical_names.end() || e.nodes.size() != 3) continue;
      std::array<int, 3> edge{};
      for (int k = 0; k < 3; ++k) {
        const auto it = index.find(e.nodes[static_cast<std::size_t>(k)]);
        if (it == index.end()) fail("a boundary line names a node of no triangle");
        edge[static_cast<std::size_t>(k)] = it->second;
      }
      mesh.groups[name->second].push_back(edge);
    }
  }
  return mesh;
}

TriMesh mesh_with_gmsh(const MeshSpec& spec, const FeTools& tools,
                       const std::filesystem::path& work_dir, const std::string& name,
                       double timeout_s) {
  const std::filesystem::path geo = work_dir / (name + ".geo"), msh = work_dir / (name + ".msh");
  {
    std::ofstream out(geo);
    out << gmsh_geo(spec);
    if (!out) throw FeFailed("cannot write " + geo.string());
  }
  ProgramRun run;
  run.program = tools.gmsh;
  run.args = {geo.filename().string(), "-2", "-o", msh.filename().string()};
  run.work_dir = work_dir;
  run.log = work_dir / (name + ".gmsh.log");
  run.timeout_s = timeout_s;
  // gmsh reads and may write option files in $HOME: give it the work directory.
  run.env = {{"HOME", work_dir.string()}, {"OMP_NUM_THREADS", "1"}};
  const ProgramResult r = run_program(run);
  const std::string tail = file_tail(run.log, 1500);
  if (r.timed_out) {
    throw FeFailed("gmsh did not finish within " + num(timeout_s) + " s; its log ends:\n" + tail);
  }
  if (r.exit_status != 0 || !std::filesystem::exists(msh)) {
    throw FeFailed("gmsh failed (exit status " + std::to_string(r.exit_status) +
                   "); its log ends:\n" + tail);
  }
  std::ifstream in(msh);
  std::ostringstream text;
  text << in.rdbuf();
  try {
    return read_msh22(text.str());
  } catch (const std::runtime_error& e) {
    throw FeFailed(std::string(e.what()) + "; gmsh's log ends:\n" + tail);
  }
}

PolygonPieces polygon_curves(const geometry::Polygon& poly, std::vector<std::size_t> cuts,
                             double corner_rad, bool cut_chord_jumps) {
  const std::size_t n = poly.size();
  if (n < 3) throw std::invalid_argument("polygon_curves: fewer than three vertices");
  // Also where the chords' lengths jump (a straight flank's one chord beside
  // a fillet's samples): a spline through a long chord between short ones
  // overshoots, and gmsh put the mid-side node of a rack fillet's element
  // beyond its end node (a non-positive Jacobian in CalculiX, at a pressure
  // angle of 16.5 degrees). The long chord becomes a Line of its own.
  constexpr double kChordJump = 4.0;
  for (std::size_t i = 0; i < n; ++i) {
    const Point in = poly[i] - poly[(i + n - 1) % n], out = poly[(i + 1) % n] - poly[i];
    const double li = geometry::norm(in), lo = geometry::norm(out);
    if (std::abs(std::atan2(geometry::cross(in, out), geometry::dot(in, out))) > corner_rad ||
        (cut_chord_jumps && std::max(li, lo) > kChordJump * std::min(li, lo))) {
      cuts.push_back(i);
    }
  }
  for (std::size_t c : cuts) {
    if (c >= n) throw std::invalid_argument("polygon_curves: a cut past the last vertex");
  }
  std::sort(cuts.begin(), cuts.end());
  cuts.erase(std::unique(cuts.begin(), cuts.end()), cuts.end());
  if (cuts.empty()) cuts.push_back(0);
  if (cuts.size() == 1) cuts.push_back((cuts[0] + n / 2) % n);
  std::sort(cuts.begin(), cuts.end());
  PolygonPieces out;
  for (std::size_t k = 0; k < cuts.size(); ++k) {
    const std::size_t first = cuts[k], last = k + 1 < cuts.size() ? cuts[k + 1] : cuts[0] + n;
    Curve c;
    for (std::size_t i = first; i <= last; ++i) c.points.push_back(poly[i % n]);
    c.kind = c.points.size() == 2 ? Curve::Kind::Line : Curve::Kind::Spline;
    out.curves.push_back(std::move(c));
    out.first_vertex.push_back(first);
  }
  return out;
}

}  // namespace gearsph::fe
