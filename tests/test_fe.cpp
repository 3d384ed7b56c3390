// The finite-element check (fe/): its parts on inputs with known answers
// (a mesh file, a results file, tractions), then the whole pipeline (gmsh,
// CalculiX) against elasticity: a cantilever against beam theory, a thick
// cylinder against Lame, and the gear's fillet against ISO 6336-3 with its
// mesh convergence. Coarse meshes keep it to seconds. Tests that need gmsh
// and ccx skip, saying why, where they are missing.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <thread>

#include "fe/calculix_solver.hpp"
#include "fe/external_program.hpp"
#include "fe/fe_check.hpp"
#include "fe/gear_fe_job.hpp"
#include "fe/gmsh_mesher.hpp"
#include "solver/gear/gear_rating.hpp"
#include "solver/geometry/gear_profile.hpp"
#include "solver/job/job.hpp"

namespace gearsph::fe {
namespace {

namespace fs = std::filesystem;
constexpr double kPi = std::numbers::pi;

#define REQUIRE_FE_TOOLS()                                               \
  do {                                                                   \
    if (const std::string why = fe_unavailable_reason(); !why.empty()) { \
      GTEST_SKIP() << why;                                               \
    }                                                                    \
  } while (false)

// An environment variable set for one scope.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    ::setenv(name, value, 1);
  }
  ~ScopedEnv() {
    if (old_.empty()) {
      ::unsetenv(name_);
    } else {
      ::setenv(name_, old_.c_str(), 1);
    }
  }

 private:
  const char* name_;
  std::string old_;
};

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// ------------------------------------------------------------ mesh files --

// Two six-node triangles on the unit square, the second listed clockwise.
const char* kTwoTriangles = R"($MeshFormat
2.2 0 8
$EndMeshFormat
$PhysicalNames
2
1 2 "left"
2 1 "body"
$EndPhysicalNames
$Nodes
9
1 0 0 0
2 1 0 0
3 1 1 0
4 0 1 0
5 0.5 0 0
6 1 0.5 0
7 0.5 0.5 0
8 0.5 1 0
9 0 0.5 0
$EndNodes
$Elements
4
1 15 2 0 1 1
2 8 2 2 4 4 1 9
3 9 2 1 1 1 2 3 5 6 7
4 9 2 1 1 1 3 4 7 8 9
$EndElements
)";

TEST(FeMesh, ReadsGmshFilesAndTurnsTrianglesCounterClockwise) {
  const TriMesh m = read_msh22(kTwoTriangles);
  ASSERT_EQ(m.nodes.size(), 9u);
  ASSERT_EQ(m.elements.size(), 2u);
  for (const auto& e : m.elements) {
    const Point a = m.nodes[e[0]], b = m.nodes[e[1]], c = m.nodes[e[2]];
    EXPECT_GT(geometry::cross(b - a, c - a), 0.0);
    // Mid-side nodes stay between their corners.
    for (int k = 0; k < 3; ++k) {
      const Point mid = 0.5 * (m.nodes[e[k]] + m.nodes[e[(k + 1) % 3]]);
      EXPECT_LT(geometry::norm(m.nodes[e[3 + k]] - mid), 1e-15);
    }
  }
  ASSERT_EQ(m.groups.count("left"), 1u);
  EXPECT_EQ(group_nodes(m, "left").size(), 3u);
  // The square's boundary: four sides of two edges... of one edge each here.
  const std::vector<BoundaryEdge> edges = boundary_edges(m);
  EXPECT_EQ(edges.size(), 4u);
  const std::vector<BoundaryEdge> left = group_edges(m, edges, "left");
  ASSERT_EQ(left.size(), 1u);
  // Outward normal of the left side points to -x.
  const Point t = edge_tangent(m, left[0], 0.5);
  EXPECT_LT(t.y, 0.0);
  EXPECT_THROW(read_msh22("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n"), std::runtime_error);
}

TEST(FeMesh, TractionForcesAddUpToTheLoadAndItsMoment) {
  const TriMesh m = read_msh22(kTwoTriangles);
  const std::vector<BoundaryEdge> left = group_edges(m, boundary_edges(m), "left");
  // A linear traction t_x = -(1 + 2 y) on x = 0: force -2, moment about the
  // origin sum(-y fx) = integral of y (1 + 2y) dy = 1/2 + 2/3.
  const auto f = traction_forces(m, left, [](Point x, Point) {
    return Point{-(1.0 + 2.0 * x.y), 0.0};
  });
  Point total;
  double moment = 0.0;
  for (std::size_t i = 0; i < f.size(); ++i) {
    total = total + f[i];
    moment += geometry::cross(m.nodes[i], f[i]);
  }
  EXPECT_NEAR(total.x, -2.0, 1e-12);
  EXPECT_NEAR(total.y, 0.0, 1e-15);
  EXPECT_NEAR(moment, 0.5 + 2.0 / 3.0, 1e-12);
  // A pressure (along the outward normal): pushes +x on the left side.
  const auto p = traction_forces(m, left, [](Point, Point n) { return -3.0 * n; });
  double px = 0.0;
  for (const Point& q : p) px += q.x;
  EXPECT_NEAR(px, 3.0, 1e-12);
}

TEST(FeMesh, NearestEdgeAndValuesAlongIt) {
  const TriMesh m = read_msh22(kTwoTriangles);
  const std::vector<BoundaryEdge> edges = boundary_edges(m);
  const EdgeHit hit = nearest_edge(m, edges, {0.3, -0.01});
  EXPECT_NEAR(hit.distance, 0.01, 1e-9);
  const BoundaryEdge& e = edges[hit.edge];
  EXPECT_NEAR(edge_point(m, e, hit.xi).x, 0.3, 1e-9);
  // A quadratic nodal field is read back exactly: f = x^2 on the bottom.
  std::vector<double> f;
  for (const Point& p : m.nodes) f.push_back(p.x * p.x);
  EXPECT_NEAR(along_edge(e, hit.xi, f), 0.09, 1e-9);
}

TEST(FeMesh, PolygonIsCutIntoSplinesAtCornersAndGivenVertices) {
  geometry::Polygon square;
  for (int k = 0; k < 4; ++k) square.push_back({k == 1 || k == 2 ? 1.0 : 0.0, k >= 2 ? 1.0 : 0.0});
  const PolygonPieces sq = polygon_curves(square, {}, 0.5);
  ASSERT_EQ(sq.curves.size(), 4u);
  for (const Curve& c : sq.curves) EXPECT_EQ(c.kind, Curve::Kind::Line);
  geometry::Polygon circle;
  for (int k = 0; k < 90; ++k)
    circle.push_back({std::cos(2 * kPi * k / 90), std::sin(2 * kPi * k / 90)});
  const PolygonPieces c = polygon_curves(circle, {10, 50}, 0.5);
  ASSERT_EQ(c.curves.size(), 2u);
  EXPECT_EQ(c.curves[0].kind, Curve::Kind::Spline);
  EXPECT_EQ(c.curves[0].points.size(), 41u);
  EXPECT_EQ(c.curves[1].points.size(), 51u);  // wraps past the first vertex
  // The .geo names every curve in one closed loop.
  MeshSpec spec;
  spec.loops = {c.curves};
  spec.size_max = 0.1;
  const std::string geo = gmsh_geo(spec);
  EXPECT_NE(geo.find("Spline(1)"), std::string::npos);
  EXPECT_NE(geo.find("Curve Loop(1) = {1, 2};"), std::string::npos);
  spec.loops[0].pop_back();
  EXPECT_THROW(gmsh_geo(spec), std::invalid_argument);
}

// A straight chord between finely sampled arcs (a rack's flank between its
// fillet and its tip rounding): a Line of its own, not a spline segment,
// which would overshoot between samples 270 times shorter and put mid-side
// nodes outside their elements.
TEST(FeMesh, ALongChordBetweenShortOnesIsALineOfItsOwn) {
  geometry::Polygon d;  // a D: a half circle of 60 samples closed by its diameter
  for (int k = 0; k <= 60; ++k) d.push_back({std::cos(kPi * k / 60), std::sin(kPi * k / 60)});
  const PolygonPieces p = polygon_curves(d, {}, 2.0, true);  // no corner cuts
  ASSERT_EQ(p.curves.size(), 2u);
  std::size_t lines = 0;
  for (const Curve& c : p.curves) {
    if (c.kind == Curve::Kind::Line) {
      ++lines;
      ASSERT_EQ(c.points.size(), 2u);
      EXPECT_NEAR(geometry::norm(c.points[1] - c.points[0]), 2.0, 1e-12);  // the diameter
    }
  }
  EXPECT_EQ(lines, 1u);
  // Chords of even length are left as they were: the circle is cut only
  // where it is asked.
  geometry::Polygon circle;
  for (int k = 0; k < 90; ++k)
    circle.push_back({std::cos(2 * kPi * k / 90), std::sin(2 * kPi * k / 90)});
  EXPECT_EQ(polygon_curves(circle, {10, 50}, 2.0, true).curves.size(), 2u);
  // Without the rule the D is one spline, from its only cut.
  EXPECT_EQ(polygon_curves(d, {}, 2.0).curves.size(), 2u);
  EXPECT_EQ(polygon_curves(d, {}, 2.0).curves[0].kind, Curve::Kind::Spline);
}

// --------------------------------------------------------- results files --

TEST(FeResults, ReadsFixedWidthFrdRecordsAndTheReactionTotal) {
  // Numbers packed without separators, as ccx writes them.
  const std::string frd =
      "    1C\n"
      "    2C                             2                                     1\n"
      " -1         1 0.00000E+00 0.00000E+00 0.00000E+00\n"
      " -3\n"
      "  100CL  101 1.000000000           2                     0    1           1\n"
      " -4  DISP        4    1\n"
      " -5  D1          1    2    1    0\n"
      " -1         1-1.30155E-06-1.74248E-05 0.00000E+00\n"
      " -1         2 2.00000E-06 3.00000E-06 0.00000E+00\n"
      " -3\n"
      "  100CL  101 1.000000000           2                     0    1           1\n"
      " -4  STRESS      6    1\n"
      " -1         1-8.82740E+06-2.35361E+06-3.35430E+06-2.01064E+06 7.52278E-14 5.71037E-14\n"
      " -1         2 1.00000E+08 2.00000E+08 9.00000E+07 5.00000E+07 0.00000E+00 0.00000E+00\n"
      " -1         9 1.00000E+08 2.00000E+08 9.00000E+07 5.00000E+07 0.00000E+00 0.00000E+00\n"
      " -3\n"
      " 9999\n";
  const FeSolution s = read_frd(frd, 2);
  EXPECT_DOUBLE_EQ(s.displacement[0].x, -1.30155e-6);
  EXPECT_DOUBLE_EQ(s.displacement[0].y, -1.74248e-5);
  EXPECT_DOUBLE_EQ(s.stress[0].xx, -8.82740e6);
  EXPECT_DOUBLE_EQ(s.stress[0].zz, -3.35430e6);
  EXPECT_DOUBLE_EQ(s.stress[0].xy, -2.01064e6);
  EXPECT_DOUBLE_EQ(s.stress[1].yy, 2e8);
  EXPECT_THROW(read_frd(frd, 3), std::runtime_error);  // node 3 has no results
  const std::string dat =
      "\n total force (fx,fy,fz) for set SUPPORTED and time  0.1000000E+01\n\n"
      "        1.305943E-08  1.000000E+03 -5.019314E-16\n";
  const Point r = read_reaction_total(dat);
  EXPECT_DOUBLE_EQ(r.y, 1000.0);
  EXPECT_THROW(read_reaction_total("nothing"), std::runtime_error);
}

TEST(FeResults, PlaneStrainStressMeasures) {
  NodalStress s{100.0, -50.0, 15.0, 40.0};
  const double c = 25.0, r = std::sqrt(75.0 * 75.0 + 40.0 * 40.0);
  EXPECT_NEAR(s.max_principal(), c + r, 1e-12);
  EXPECT_NEAR(s.min_principal(), c - r, 1e-12);
  EXPECT_NEAR(s.von_mises(),
              std::sqrt(0.5 * (150.0 * 150.0 + 65.0 * 65.0 + 85.0 * 85.0) + 3.0 * 1600.0), 1e-9);
}

TEST(FeTools, MissingProgramsAreReportedNotCrashedOn) {
  {
    ScopedEnv env("GEARSPH_CCX", "/nonexistent/ccx");
    const std::string why = fe_unavailable_reason();
    EXPECT_EQ(why.rfind("FE unavailable: ", 0), 0u) << why;
    EXPECT_NE(why.find("GEARSPH_CCX=/nonexistent/ccx"), std::string::npos) << why;
    EXPECT_THROW(find_fe_tools(), FeUnavailable);
  }
  {
    ScopedEnv env("PATH", "/nonexistent");
    const std::string why = fe_unavailable_reason();
    EXPECT_NE(why.find("gmsh is not on PATH"), std::string::npos) << why;
    EXPECT_NE(why.find("ccx is not on PATH"), std::string::npos) << why;
  }
}

TEST(FeTools, ProgramsRunInTheirDirectoryAndAreStoppedAtTheTimeout) {
  WorkDir dir("gearsph-fe-test-");
  ProgramRun run;
  run.program = "/bin/sh";
  run.args = {"-c", "pwd; echo $GEARSPH_TEST_VALUE; exit 3"};
  run.work_dir = dir.path();
  run.log = dir.path() / "log";
  run.env = {{"GEARSPH_TEST_VALUE", "seven"}};
  const ProgramResult r = run_program(run);
  EXPECT_EQ(r.exit_status, 3);
  EXPECT_FALSE(r.timed_out);
  const std::string log = slurp(run.log);
  EXPECT_NE(log.find(fs::canonical(dir.path()).string()), std::string::npos) << log;
  EXPECT_NE(log.find("seven"), std::string::npos) << log;
  run.args = {"-c", "sleep 30 & sleep 30"};  // a child of its own, stopped too
  run.timeout_s = 0.3;
  const ProgramResult slow = run_program(run);
  EXPECT_TRUE(slow.timed_out);
  EXPECT_LT(slow.wall_s, 5.0);
  run.program = "/nonexistent/program";
  EXPECT_THROW(run_program(run), FeFailed);
}

using namespace std::chrono_literals;

// A process that exists and is not a zombie (an orphan's zombie stays until
// its new parent reaps it, which a container's init may never do).
bool alive(pid_t pid) {
  if (::kill(pid, 0) != 0) return false;
  const std::string stat = slurp("/proc/" + std::to_string(pid) + "/stat");
  const auto close = stat.rfind(')');
  return close == std::string::npos || close + 2 >= stat.size() || stat[close + 2] != 'Z';
}

// N2: a hung tool (a stand-in shell script that never ends, with a child
// of its own) is stopped, group and all, once its caller's stop says so.
TEST(FeTools, AHungToolStopsWhenAsked) {
  WorkDir dir("gearsph-fe-test-");
  ProgramRun run;
  run.program = "/bin/sh";
  run.args = {"-c", "sleep 300 & echo $! > child.pid; wait"};
  run.work_dir = dir.path();
  run.log = dir.path() / "log";
  run.timeout_s = 300;
  std::atomic<bool> stop{false};
  std::thread asker([&] {
    // Asked once the stand-in has started its child.
    while (!fs::exists(dir.path() / "child.pid")) std::this_thread::sleep_for(10ms);
    std::this_thread::sleep_for(100ms);
    stop = true;
  });
  {
    const ProgramStopScope scope([&] { return stop.load(); });
    EXPECT_THROW(run_program(run), ProgramStopped);
  }
  asker.join();
  const pid_t child = std::stoi(slurp(dir.path() / "child.pid"));
  std::this_thread::sleep_for(100ms);
  EXPECT_FALSE(alive(child)) << "the tool's own child outlived the stop";
}

// N3: a process killed with SIGKILL while its tool runs takes the tool
// with it (the parent-death signal), and its work folder is removed by the
// next start.
TEST(FeTools, AToolDiesWithItsParentAndItsFolderIsRemovedLater) {
  WorkDir scratch("gearsph-test-scratch-");
  const fs::path pid_file = scratch.path() / "tool.pid";
  fs::path folder;
  const pid_t parent = ::fork();
  ASSERT_GE(parent, 0);
  if (parent == 0) {
    WorkDir work("gearsph-fe-");
    ProgramRun run;
    run.program = "/bin/sh";
    run.args = {"-c", "echo $$ > " + pid_file.string() + ".tmp; mv " + pid_file.string() + ".tmp " +
                          pid_file.string() + "; exec sleep 300"};
    run.work_dir = work.path();
    run.log = work.path() / "log";
    run.timeout_s = 300;
    std::ofstream(scratch.path() / "folder") << work.path().string();
    run_program(run);
    ::_exit(0);
  }
  const auto until = std::chrono::steady_clock::now() + 30s;
  while (!fs::exists(pid_file) && std::chrono::steady_clock::now() < until) {
    std::this_thread::sleep_for(10ms);
  }
  ASSERT_TRUE(fs::exists(pid_file));
  const pid_t tool = std::stoi(slurp(pid_file));
  folder = slurp(scratch.path() / "folder");
  ::kill(parent, SIGKILL);
  int status = 0;
  ::waitpid(parent, &status, 0);
  // The tool is not our child: it is gone once kill(tool, 0) fails.
  bool gone = false;
  for (int i = 0; i < 500 && !gone; ++i) {
    gone = !alive(tool);
    if (!gone) std::this_thread::sleep_for(10ms);
  }
  EXPECT_TRUE(gone) << "the tool outlived its parent";
  ASSERT_TRUE(fs::exists(folder));
  EXPECT_GE(remove_stale_work_dirs("gearsph-fe-"), 1);
  EXPECT_FALSE(fs::exists(folder));
}

// ------------------------------------------------------------ elasticity --

// Plane-strain moduli: E' = E / (1 - nu^2) in bending.
struct Elastic {
  double E = 2.1e11, nu = 0.3;
  double E_plane() const { return E / (1.0 - nu * nu); }
};

Curve line(Point a, Point b, const std::string& group) {
  Curve c;
  c.kind = Curve::Kind::Line;
  c.points = {a, b};
  c.group = group;
  return c;
}

Curve arc(Point a, Point b, const std::string& group) {
  Curve c;
  c.kind = Curve::Kind::Arc;
  c.points = {a, b};
  c.group = group;
  return c;
}

// A boundary group's nodal values read at a point on it.
double on_group(const TriMesh& m, const std::string& group, Point p,
                const std::vector<double>& nodal) {
  const std::vector<BoundaryEdge> edges = group_edges(m, boundary_edges(m), group);
  const EdgeHit hit = nearest_edge(m, edges, p);
  EXPECT_LT(hit.distance, 1e-9);
  return along_edge(edges[hit.edge], hit.xi, nodal);
}

// Cantilever L x H (L = 10 H), clamped at x = 0, shear force P at x = L as
// the parabolic traction of the elasticity solution (Timoshenko & Goodier,
// Theory of Elasticity, 3rd ed., 1970, sec. 21). Away from the clamp and
// the load: bending stress M y / I, and the deflection's curvature M / (E' I)
// (the shear deflection of Timoshenko's beam is linear in x: it drops out
// of the second difference).
TEST(FePipeline, CantileverAgainstBeamTheory) {
  REQUIRE_FE_TOOLS();
  const double L = 0.1, H = 0.01, P = 1000.0;  // P in N per metre of thickness
  const Elastic mat;
  MeshSpec spec;
  spec.size_max = H / 8.0;
  spec.loops = {{line({0, -H / 2}, {L, -H / 2}, "bottom"), line({L, -H / 2}, {L, H / 2}, "end"),
                 line({L, H / 2}, {0, H / 2}, "top"), line({0, H / 2}, {0, -H / 2}, "root")}};
  const FeTools tools = find_fe_tools();
  WorkDir dir("gearsph-fe-test-");
  FeModel model;
  model.mesh = mesh_with_gmsh(spec, tools, dir.path(), "cantilever", 60);
  model.E_Pa = mat.E;
  model.nu = mat.nu;
  model.supports.push_back({group_nodes(model.mesh, "root"), true, true});
  const auto end = group_edges(model.mesh, boundary_edges(model.mesh), "end");
  model.nodal_forces = traction_forces(model.mesh, end, [&](Point x, Point) {
    const double eta = 2.0 * x.y / H;
    return Point{0.0, -1.5 * P / H * (1.0 - eta * eta)};
  });
  const FeSolution s = solve_with_calculix(model, tools, dir.path(), "cantilever", 1, 60);
  EXPECT_NEAR(s.reaction.y, P, 1e-4 * P);
  EXPECT_NEAR(s.reaction.x, 0.0, 1e-4 * P);

  const double I = H * H * H / 12.0;
  std::vector<double> sxx, v;
  for (const NodalStress& n : s.stress) sxx.push_back(n.xx);
  for (const Point& u : s.displacement) v.push_back(u.y);
  for (double xf : {0.3, 0.5, 0.7}) {
    const double x = xf * L, M = P * (L - x);  // hogging: tension on top
    const double top = on_group(model.mesh, "top", {x, H / 2}, sxx);
    const double bottom = on_group(model.mesh, "bottom", {x, -H / 2}, sxx);
    const double beam = M * (H / 2) / I;
    std::printf("cantilever x = %.2f L: sigma_xx top %.7g, bottom %.7g, beam theory +-%.7g Pa\n",
                xf, top, bottom, beam);
    EXPECT_NEAR(top / beam, 1.0, 0.005);
    EXPECT_NEAR(-bottom / beam, 1.0, 0.005);
  }
  const double x = 0.5 * L, d = 0.15 * L;
  const double curvature = (on_group(model.mesh, "top", {x - d, H / 2}, v) -
                            2.0 * on_group(model.mesh, "top", {x, H / 2}, v) +
                            on_group(model.mesh, "top", {x + d, H / 2}, v)) /
                           (d * d);
  const double beam_curvature = -P * (L - x) / (mat.E_plane() * I);
  std::printf("cantilever curvature at L/2: %.7g 1/m, beam theory %.7g 1/m\n", curvature,
              beam_curvature);
  EXPECT_NEAR(curvature / beam_curvature, 1.0, 0.005);
}

// A quarter of a thick cylinder a..b under internal pressure p, plane
// strain, held by its symmetry planes: Lame's bore hoop stress
// p (b^2 + a^2) / (b^2 - a^2) and bore displacement
// (1 + nu) p a^2 / (E (b^2 - a^2)) [(1 - 2 nu) a + b^2 / a] (Timoshenko &
// Goodier sec. 28, plane strain), within 0.5 %.
TEST(FePipeline, ThickCylinderAgainstLame) {
  REQUIRE_FE_TOOLS();
  const double a = 0.01, b = 0.02, p = 1e8;
  const Elastic mat;
  MeshSpec spec;
  spec.size_max = (b - a) / 8.0;
  spec.loops = {{line({a, 0}, {b, 0}, "y_plane"), arc({b, 0}, {0, b}, "outer"),
                 line({0, b}, {0, a}, "x_plane"), arc({0, a}, {a, 0}, "bore")}};
  SizeZone bore;
  bore.curves = {{0, 3}};
  bore.size_min = (b - a) / 16.0;
  bore.size_max = spec.size_max;
  bore.dist_min = 0.1 * (b - a);
  bore.dist_max = 0.5 * (b - a);
  spec.zones = {bore};
  const FeTools tools = find_fe_tools();
  WorkDir dir("gearsph-fe-test-");
  FeModel model;
  model.mesh = mesh_with_gmsh(spec, tools, dir.path(), "cylinder", 60);
  model.E_Pa = mat.E;
  model.nu = mat.nu;
  model.supports.push_back({group_nodes(model.mesh, "y_plane"), false, true});
  model.supports.push_back({group_nodes(model.mesh, "x_plane"), true, false});
  const auto bore_edges = group_edges(model.mesh, boundary_edges(model.mesh), "bore");
  model.nodal_forces =
      traction_forces(model.mesh, bore_edges, [p](Point, Point n) { return -p * n; });
  const FeSolution s = solve_with_calculix(model, tools, dir.path(), "cylinder", 1, 60);

  const double hoop = p * (b * b + a * a) / (b * b - a * a);
  const double u_bore = (1.0 + mat.nu) * p * a * a / (mat.E * (b * b - a * a)) *
                        ((1.0 - 2.0 * mat.nu) * a + b * b / a);
  for (double deg : {15.0, 45.0, 75.0}) {
    const double th = deg * kPi / 180.0;
    const Point at{a * std::cos(th), a * std::sin(th)}, t{-std::sin(th), std::cos(th)};
    std::vector<double> s_tt, u_r;
    for (const NodalStress& n : s.stress) {
      s_tt.push_back(t.x * t.x * n.xx + 2.0 * t.x * t.y * n.xy + t.y * t.y * n.yy);
    }
    for (const Point& u : s.displacement) u_r.push_back(u.x * std::cos(th) + u.y * std::sin(th));
    const double fe_hoop = on_group(model.mesh, "bore", at, s_tt);
    const double fe_u = on_group(model.mesh, "bore", at, u_r);
    std::printf(
        "thick cylinder at %.0f deg: bore hoop %.6g Pa (Lame %.6g), bore u_r %.6g m "
        "(Lame %.6g)\n",
        deg, fe_hoop, hoop, fe_u, u_bore);
    EXPECT_NEAR(fe_hoop / hoop, 1.0, 0.005);
    EXPECT_NEAR(fe_u / u_bore, 1.0, 0.005);
  }
}

// ------------------------------------------------------------------ gear --

nlohmann::json gear_job(const nlohmann::json& contact_point, double load_N = 7000.0) {
  return validate_job({{"name", "fe-test"},
                       {"scene",
                        {{"type", "rack_pinion"},
                         {"quasi_static", true},
                         {"contact_point", contact_point},
                         {"pinion", {{"omega_rad_s", 0}}},
                         {"rack", {{"velocity_m_s", 0}, {"load_N", load_N}}}}}});
}

// ISO 6336-3 method B rates the root with sigma_F0 = F_t/(b m) Y_F Y_S at
// the 30-degree point, to the accuracy of its formulas (validation.md
// section 7: 15-20 %). Coarse meshes here (0.4 and 0.2 mm at the
// fillets): their peaks agree within 1 %, and the fine pair of
// `gearsph fe` (docs/fe-check.md) within 0.1 %.
TEST(FeGear, FilletStressAgainstIsoAtPitchHpstcAndTip) {
  REQUIRE_FE_TOOLS();
  WorkDir dir("gearsph-fe-test-");
  FeCheckOptions o;
  o.fillet_sizes_m = {0.4e-3, 0.2e-3};
  o.images = false;
  double compliance_below = 0.0, pair_above = 1e300;
  for (const char* point : {"pitch", "hpstc", "tip"}) {
    const nlohmann::json s = run_fe_check(gear_job(point), dir.path() / point, o);
    // The pinion's compliance at the load's centre: converged between the
    // two meshes, and larger the higher the load sits on the tooth (its
    // lever arm, and so its bending, grows).
    const double compliance = s.at("pinion_compliance_at_load_um_mm_per_N").get<double>();
    const double compliance_diff = s.at("coarse_fine_difference")
                                       .at("pinion_compliance_at_load_um_mm_per_N")
                                       .at("relative_difference");
    std::printf("%-5s pinion compliance at the load %.4f um mm/N, coarse-fine %+.3f %%\n", point,
                compliance, 100.0 * compliance_diff);
    EXPECT_GT(compliance, compliance_below) << point;
    EXPECT_LT(std::abs(compliance_diff), 0.02) << point;
    compliance_below = compliance;
    // The rack's tooth under the same pressure, and the pair in series:
    // converged, and stiffer the nearer the load sits to the pitch point.
    // At the pitch point it is ISO 6336-1's theoretical single-pair
    // stiffness c'_th (the ideal elastic pair, c' / C_M) to within ISO's
    // own accuracy.
    const double pair = s.at("pair_mesh_stiffness_N_per_mm_um").get<double>();
    const double rack_diff =
        s.at("coarse_fine_difference").at("rack_compliance_um_mm_per_N").at("relative_difference");
    std::printf("%-5s rack compliance %.4f um mm/N, coarse-fine %+.3f %%; pair %.2f N/(mm um)\n",
                point, s.at("rack_compliance_um_mm_per_N").get<double>(), 100.0 * rack_diff, pair);
    EXPECT_GT(s.at("rack_compliance_um_mm_per_N").get<double>(), 0.0) << point;
    EXPECT_LT(std::abs(rack_diff), 0.03) << point;
    EXPECT_LT(pair, pair_above) << point;
    pair_above = pair;
    // The pair's stiffness takes each body at the patch centre: the bodies'
    // approach. The pressure-weighted means lie below the centres by the
    // surfaces' gap x^2 / (2 R*) averaged over the Hertz pressure, a^2 /
    // (8 R*) = F' / (2 pi E*) (Johnson 1985, eqs. 4.43-4.45): a compliance
    // of 1 / (2 pi E*) whatever the load and the curvature.
    {
      const GearFeJob read = read_gear_fe_job(gear_job(point));
      const double e_star =
          1.0 / ((1.0 - read.model.nu * read.model.nu) / read.model.E_Pa +
                 (1.0 - read.model.rack_nu * read.model.rack_nu) / read.model.rack_E_Pa);
      const double hertz_gap = 1e9 / (2.0 * 3.141592653589793 * e_star);  // um mm/N
      const double gap = s.at("pinion_compliance_at_centre_um_mm_per_N").get<double>() -
                         s.at("pinion_compliance_at_load_um_mm_per_N").get<double>() +
                         s.at("rack_compliance_at_centre_um_mm_per_N").get<double>() -
                         s.at("rack_compliance_um_mm_per_N").get<double>();
      std::printf("%-5s centres less means %.5f um mm/N against Hertz's 1 / (2 pi E*) %.5f\n",
                  point, gap, hertz_gap);
      EXPECT_NEAR(gap / hertz_gap, 1.0, 0.1) << point;
    }
    if (std::string(point) == "pitch") {
      const GearFeJob read = read_gear_fe_job(gear_job(point));
      const geometry::PinionGeometry pinion(read.model.pinion);
      const double c_th =
          1e-9 * gear::iso_single_pair_stiffness(pinion, read.model.E_Pa, read.model.rack_E_Pa) /
          gear::kIsoMeasuredOverTheoretical;
      std::printf("pitch: pair %.2f against ISO c'_th %.2f N/(mm um) (%+.1f %%)\n", pair, c_th,
                  100.0 * (pair / c_th - 1.0));
      EXPECT_NEAR(pair / c_th, 1.0, 0.15);
    }
    const nlohmann::json& iso = s.at("iso_6336_3");
    const double peak = s.at("fillet_tension_peak_Pa").get<double>();
    const double at30 = s.at("fillet_stress_at_iso30_Pa").get<double>();
    const double sigma_F0 = iso.at("sigma_F0_Pa").get<double>();
    const double diff =
        s.at("coarse_fine_difference").at("fillet_tension_peak_Pa").at("relative_difference");
    std::printf(
        "%-5s r = %.3f mm: FE tension peak %.2f MPa, at 30 deg %.2f MPa, ISO sigma_F0 "
        "%.2f MPa (peak %+.1f %%, 30 deg %+.1f %%); coarse-fine %+.3f %%\n",
        point, 1e3 * s.at("load_radius_m").get<double>(), 1e-6 * peak, 1e-6 * at30, 1e-6 * sigma_F0,
        100.0 * (peak / sigma_F0 - 1.0), 100.0 * (at30 / sigma_F0 - 1.0), 100.0 * diff);
    EXPECT_NEAR(peak / sigma_F0, 1.0, 0.15) << point;
    EXPECT_NEAR(at30 / sigma_F0, 1.0, 0.15) << point;
    EXPECT_LT(std::abs(diff), 0.01) << point;
    // Equilibrium: the support carries the load. The fillet samples lie on
    // the mesh's boundary (within 1 % of an element: the quadratic edges
    // across the kink of curvature where the root circle meets the
    // trochoid are 1.5 um off at 0.4 mm).
    for (const nlohmann::json& m : s.at("meshes")) {
      EXPECT_LT(m.at("reaction_imbalance").get<double>(), 1e-4) << point;
      EXPECT_LT(m.at("curve_to_mesh_distance_m").get<double>(),
                0.01 * m.at("fillet_size_m").get<double>())
          << point;
    }
    // The peak sits on the fillet between the root circle and the form
    // circle, the compression fillet's lowest stress is a compression.
    EXPECT_GT(s.at("fillet_tension_peak_radius_m").get<double>(), 0.019);
    EXPECT_LT(s.at("fillet_compression_peak_Pa").get<double>(), 0.0);
    // The stress figures' colour scale: +-1.25 times the larger fillet peak.
    const double cap = 1.25 * std::max(peak, -s.at("fillet_compression_peak_Pa").get<double>());
    EXPECT_NEAR(s.at("image_range_Pa").at(0).get<double>(), -cap, 1e-6 * cap) << point;
    EXPECT_NEAR(s.at("image_range_Pa").at(1).get<double>(), cap, 1e-6 * cap) << point;
    EXPECT_TRUE(fs::exists(dir.path() / point / "fe_summary.json"));
    EXPECT_TRUE(fs::exists(dir.path() / point / "fe_fillet_curves.csv"));
  }
}

TEST(FeGear, LoadIsLinearAndFollowsTheFlankSide) {
  REQUIRE_FE_TOOLS();
  WorkDir dir("gearsph-fe-test-");
  FeCheckOptions o;
  o.fillet_sizes_m = {0.4e-3};
  o.images = false;
  const nlohmann::json full = run_fe_check(gear_job("pitch", 7000.0), dir.path() / "a", o);
  const nlohmann::json half = run_fe_check(gear_job("pitch", 3500.0), dir.path() / "b", o);
  EXPECT_NEAR(half.at("fillet_tension_peak_Pa").get<double>() /
                  full.at("fillet_tension_peak_Pa").get<double>(),
              0.5, 1e-4);
  // A pinion turning the other way loads the other flank: the mirror image.
  nlohmann::json ccw = gear_job("pitch");
  ccw["scene"]["pinion"]["omega_rad_s"] = 1.0;
  const nlohmann::json m = run_fe_check(ccw, dir.path() / "c", o);
  EXPECT_NEAR(m.at("fillet_tension_peak_Pa").get<double>() /
                  full.at("fillet_tension_peak_Pa").get<double>(),
              1.0, 0.01);
  EXPECT_LT(m.at("load").at("direction")[0].get<double>(), 0.0);
  EXPECT_GT(full.at("load").at("direction")[0].get<double>(), 0.0);
  // Tooth 0's force: F_n = F_t / cos(20 deg) along the line of action.
  EXPECT_NEAR(full.at("load").at("normal_force_N").get<double>(), 7000.0 / std::cos(kPi / 9.0),
              1e-9);
  const auto applied = full.at("applied_force_N");
  EXPECT_NEAR(std::hypot(applied[0].get<double>(), applied[1].get<double>()),
              7000.0 / std::cos(kPi / 9.0), 1e-6);
}

TEST(FeGear, JobsTheCheckCannotModelAreRefusedWithTheirField) {
  auto pointer_of = [](const nlohmann::json& job) {
    try {
      read_gear_fe_job(job);
    } catch (const InvalidJob& e) {
      return e.issues.at(0).pointer;
    }
    return std::string("accepted");
  };
  nlohmann::json dynamic = gear_job("pitch");
  dynamic["scene"]["quasi_static"] = false;
  EXPECT_EQ(pointer_of(dynamic), "/scene/quasi_static");
  EXPECT_EQ(pointer_of(gear_job(10.0)), "/scene/contact_point");  // 10 mm: below the root
  EXPECT_EQ(pointer_of(gear_job("tip")), "accepted");
  EXPECT_EQ(pointer_of(validate_job({{"scene", {{"type", "plate"}}}})), "/scene/type");
  // A run may ask for the check only where it applies.
  try {
    validate_job({{"scene", {{"type", "rack_pinion"}, {"fe_check", true}}}});
    ADD_FAILURE() << "fe_check on a dynamic run was taken";
  } catch (const InvalidJob& e) {
    EXPECT_EQ(e.issues.at(0).pointer, "/scene/fe_check");
  }
  try {
    validate_job(
        {{"scene", {{"type", "rack_pinion"}, {"fe_check", true}, {"quasi_static", true}}}});
    ADD_FAILURE() << "fe_check without a load was taken";
  } catch (const InvalidJob& e) {
    EXPECT_EQ(e.issues.at(0).pointer, "/scene/rack/load_N");
  }
}

// An fe_summary.json's fillet numbers, ISO's sigma_F0 and the load.
nlohmann::json fe_summary_of(double normal_force_N, const std::string& source) {
  return {
      {"fillet_tension_peak_Pa", 3.5e8},
      {"fillet_tension_peak_radius_m", 0.0205},
      {"fillet_compression_peak_Pa", -4.2e8},
      {"fillet_stress_at_iso30_Pa", 3.4e8},
      {"reference_fillet_size_m", 1e-4},
      {"load", {{"normal_force_N", normal_force_N}, {"load_radius_m", 0.0262}, {"source", source}}},
      {"iso_6336_3", {{"sigma_F0_Pa", 3.6e8}}}};
}

TEST(FeGear, ComparisonGivesSphFeAndErrorOrSaysWhatIsMissing) {
  nlohmann::json fe = fe_summary_of(7449.0, "nominal");
  fe["image_range_Pa"] = {-5.25e8, 5.25e8};
  nlohmann::json sph = {{"analysis", {{"static_check", {{"tooth0_force_N", 7449.0}}}}}};
  nlohmann::json block = fe_comparison(sph, fe);
  EXPECT_EQ(block.at("status"), "sph_values_missing");
  EXPECT_TRUE(block.at("fillet_tension_peak_Pa").at("sph").is_null());
  EXPECT_TRUE(block.at("fillet_tension_peak_Pa").at("error").is_null());
  EXPECT_EQ(block.at("fillet_tension_peak_Pa").at("fe"), 3.5e8);
  EXPECT_NE(block.at("message").get<std::string>().find("fillet_stress_at_iso30_Pa"),
            std::string::npos);
  auto& sc = sph["analysis"]["static_check"];
  sc["fillet_tension_peak_Pa"] = 3.15e8;
  sc["fillet_tension_peak_radius_m"] = 0.0205;
  sc["fillet_compression_peak_Pa"] = -4.2e8;
  sc["fillet_stress_at_iso30_Pa"] = 3.4e8;
  block = fe_comparison(sph, fe);
  EXPECT_EQ(block.at("status"), "compared");
  EXPECT_NEAR(block.at("fillet_tension_peak_Pa").at("error").get<double>(), -0.1, 1e-12);
  EXPECT_NEAR(block.at("fillet_compression_peak_Pa").at("error").get<double>(), 0.0, 1e-12);
  // The FE figures' colour scale, for the SPH field drawn beside them.
  EXPECT_EQ(block.at("image_range_Pa"), nlohmann::json({-5.25e8, 5.25e8}));
  // The pinion's compliance beside the SPH split, when both give it.
  EXPECT_FALSE(block.contains("mesh_compliance_um_mm_per_N"));
  fe["pinion_compliance_at_load_um_mm_per_N"] = 0.0429;
  sc["mesh_compliance"] = {{"pinion_um_mm_per_N", 0.0377}, {"contact_um_mm_per_N", 0.0262}};
  block = fe_comparison(sph, fe);
  const nlohmann::json& pc = block.at("mesh_compliance_um_mm_per_N");
  EXPECT_EQ(pc.at("fe_pinion_at_load"), 0.0429);
  EXPECT_EQ(pc.at("sph_pinion"), 0.0377);
  EXPECT_EQ(pc.at("sph_contact"), 0.0262);
  // The pair's stiffness against the static check's.
  EXPECT_FALSE(block.contains("mesh_stiffness_N_per_mm_um"));
  fe["pair_mesh_stiffness_N_per_mm_um"] = 13.9;
  fe["rack_compliance_um_mm_per_N"] = 0.030;
  fe["rack_compliance_at_centre_um_mm_per_N"] = 0.0308;
  sc["mesh_stiffness_N_per_mm_um"] = 12.1;
  sc["mesh_compliance"]["rack_um_mm_per_N"] = 0.0187;
  block = fe_comparison(sph, fe);
  EXPECT_EQ(block.at("mesh_compliance_um_mm_per_N").at("fe_rack_at_load"), 0.030);
  EXPECT_EQ(block.at("mesh_compliance_um_mm_per_N").at("sph_rack"), 0.0187);
  EXPECT_EQ(block.at("mesh_compliance_um_mm_per_N").at("fe_rack_at_centre"), 0.0308);
  EXPECT_NEAR(block.at("mesh_stiffness_N_per_mm_um").at("error").get<double>(), 12.1 / 13.9 - 1.0,
              1e-12);
}

// The FE model has the teeth the SPH static check of the same job models
// (tooth 0 and at least its neighbours), and under --compare or a run's
// fe_check those of the finished run, held at its hub ring's radius; the
// comparison says what each modelled.
TEST(FeGear, ModelsTheStructureTheSphStaticCheckModels) {
  auto teeth_of = [](const nlohmann::json& modelled) {
    nlohmann::json job = gear_job("pitch");
    job["scene"]["pinion"]["modelled_teeth"] = modelled;
    const GearFeCase c = read_gear_fe_job(validate_job(job)).model;
    return c.whole_gear ? std::string("all")
                        : std::to_string(c.first_tooth) + ".." + std::to_string(c.last_tooth);
  };
  EXPECT_EQ(teeth_of("auto"), "-1..1");
  EXPECT_EQ(teeth_of(1), "-1..1");
  EXPECT_EQ(teeth_of(5), "-2..2");
  EXPECT_EQ(teeth_of(4), "-1..2");
  EXPECT_EQ(teeth_of("all"), "all");

  nlohmann::json sph = {
      {"analysis", {{"static_check", {{"tooth0_force_N", 1064.0}, {"load_radius_m", 0.0262}}}}},
      {"model",
       {{"pinion",
         {{"teeth", 12},
          {"modelled_teeth", {-1, 0, 1, 2}},
          {"root_radius_m", 0.019},
          {"deformable_from_radius_m", 0.015}}},
        {"rack", {{"modelled_teeth", 1}}}}}};
  FeCheckOptions o;
  model_the_sph_run(sph, "run/summary.json", o);
  ASSERT_TRUE(o.teeth.has_value());
  EXPECT_EQ(*o.teeth, std::pair(-1, 2));
  EXPECT_FALSE(o.whole_gear);
  ASSERT_TRUE(o.rim_depth_m.has_value());
  EXPECT_NEAR(*o.rim_depth_m, 0.004, 1e-15);
  EXPECT_EQ(o.normal_force_N, 1064.0);
  EXPECT_NE(o.load_source.find("run/summary.json"), std::string::npos);

  nlohmann::json fe = fe_summary_of(1064.0, "sph");
  fe["model"] = {{"teeth", {-1, 2}}, {"fixed_radius_m", 0.015}};
  nlohmann::json st = fe_comparison(sph, fe).at("structure");
  EXPECT_EQ(st.at("same"), true) << st;
  // Three FE teeth against the run's four: said, not hidden.
  fe["model"]["teeth"] = {-1, 1};
  st = fe_comparison(sph, fe).at("structure");
  EXPECT_EQ(st.at("same"), false) << st;
  EXPECT_NE(st.at("note").get<std::string>().find("pinion teeth"), std::string::npos);
  // A whole pinion in the run and a sector in FE differ too.
  sph["model"]["pinion"]["modelled_teeth"] = nlohmann::json::array();
  for (int k = 0; k < 12; ++k) sph["model"]["pinion"]["modelled_teeth"].push_back(k);
  FeCheckOptions whole;
  model_the_sph_run(sph, "run", whole);
  EXPECT_TRUE(whole.whole_gear);
  EXPECT_EQ(fe_comparison(sph, fe).at("structure").at("same"), false);
  fe["model"]["teeth"] = "all";
  EXPECT_EQ(fe_comparison(sph, fe).at("structure").at("same"), true);
}

// ------------------------------------------------------------------- CLI --

int run_shell(const std::string& command) {
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(FeCli, MissingToolsGiveExitStatusFiveAndSaySo) {
  WorkDir dir("gearsph-fe-test-");
  const fs::path job = dir.path() / "job.json";
  nlohmann::json j = {{"scene",
                       {{"type", "rack_pinion"},
                        {"quasi_static", true},
                        {"fe_check", true},
                        {"rack", {{"load_N", 1000}}}}}};
  std::ofstream(job) << j.dump();
  const std::string env = "GEARSPH_CCX=/nonexistent/ccx ";
  const fs::path err = dir.path() / "err";
  EXPECT_EQ(run_shell(env + GEARSPH_BINARY " fe " + job.string() + " --out " +
                      (dir.path() / "fe").string() + " 2>" + err.string()),
            5);
  EXPECT_NE(slurp(err).find("FE unavailable"), std::string::npos) << slurp(err);
  EXPECT_EQ(run_shell(env + GEARSPH_BINARY " run " + job.string() + " --out " +
                      (dir.path() / "run").string() + " --quiet 2>" + err.string()),
            5);
  EXPECT_NE(slurp(err).find("/scene/fe_check"), std::string::npos) << slurp(err);
  EXPECT_FALSE(fs::exists(dir.path() / "run" / "summary.json"));
  // A dynamic job with fe_check is not a valid job (exit status 2).
  j["scene"]["quasi_static"] = false;
  std::ofstream(job) << j.dump();
  EXPECT_EQ(run_shell(GEARSPH_BINARY " run " + job.string() + " --out " +
                      (dir.path() / "run").string() + " --quiet 2>" + err.string()),
            2);
  EXPECT_NE(slurp(err).find("/scene/fe_check"), std::string::npos) << slurp(err);
}

TEST(FeCli, HelpListsEveryOption) {
  WorkDir dir("gearsph-fe-test-");
  const fs::path out = dir.path() / "help";
  ASSERT_EQ(run_shell(GEARSPH_BINARY " fe --help >" + out.string()), 0);
  const std::string help = slurp(out);
  for (const char* option :
       {"--out", "--fillet-sizes-mm", "--threads", "--rim-depth-mm", "--teeth", "--compare",
        "--keep-model-files", "--no-images", "--timeout-s", "--quiet"}) {
    EXPECT_NE(help.find(option), std::string::npos) << option;
  }
}

}  // namespace
}  // namespace gearsph::fe
