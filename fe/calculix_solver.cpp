#include "fe/calculix_solver.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>

namespace gearsph::fe {

namespace {

// ccx reads at most 20 characters a number: 12 significant digits fit
// (coordinates to 1e-14 m).
std::string num(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.12g", v);
  return text;
}

// ccx reads at most 16 entries on a data line; eight keep lines short.
void write_list(std::ostream& out, const std::vector<int>& one_based) {
  for (std::size_t i = 0; i < one_based.size(); ++i) {
    out << one_based[i] << (i + 1 == one_based.size() || i % 8 == 7 ? "\n" : ", ");
  }
}

// A fixed-width field of an .frd record: the file packs numbers without
// separators ("-1.2E+08-3.4E+08"), so columns, not spaces, delimit them.
double field(const std::string& line, std::size_t start, std::size_t width) {
  if (start + width > line.size()) throw std::runtime_error("ccx results: a record is too short");
  return std::stod(line.substr(start, width));
}

}  // namespace

double NodalStress::von_mises() const {
  return std::sqrt(0.5 * ((xx - yy) * (xx - yy) + (yy - zz) * (yy - zz) + (zz - xx) * (zz - xx)) +
                   3.0 * xy * xy);
}

double NodalStress::max_principal() const {
  return 0.5 * (xx + yy) + std::sqrt(0.25 * (xx - yy) * (xx - yy) + xy * xy);
}

double NodalStress::min_principal() const {
  return 0.5 * (xx + yy) - std::sqrt(0.25 * (xx - yy) * (xx - yy) + xy * xy);
}

std::string calculix_deck(const FeModel& model) {
  const TriMesh& mesh = model.mesh;
  if (!model.nodal_forces.empty() && model.nodal_forces.size() != mesh.nodes.size()) {
    throw std::invalid_argument("calculix deck: one nodal force per node");
  }
  std::ostringstream deck;
  deck << "** Written by gearsph (fe/calculix_solver.cpp): plane strain, unit thickness, SI.\n"
       << "*NODE, NSET=NALL\n";
  for (std::size_t i = 0; i < mesh.nodes.size(); ++i) {
    deck << i + 1 << ", " << num(mesh.nodes[i].x) << ", " << num(mesh.nodes[i].y) << "\n";
  }
  deck << "*ELEMENT, TYPE=CPE6, ELSET=EALL\n";
  for (std::size_t e = 0; e < mesh.elements.size(); ++e) {
    deck << e + 1;
    for (int v : mesh.elements[e]) deck << ", " << v + 1;
    deck << "\n";
  }
  std::set<int> all_supported;
  for (std::size_t s = 0; s < model.supports.size(); ++s) {
    std::vector<int> ids;
    for (int v : model.supports[s].nodes) {
      ids.push_back(v + 1);
      all_supported.insert(v + 1);
    }
    deck << "*NSET, NSET=SUPPORT" << s + 1 << "\n";
    write_list(deck, ids);
  }
  deck << "*NSET, NSET=SUPPORTED\n";
  write_list(deck, {all_supported.begin(), all_supported.end()});
  deck << "*MATERIAL, NAME=ELASTIC\n*ELASTIC\n"
       << num(model.E_Pa) << ", " << num(model.nu) << "\n"
       << "*SOLID SECTION, ELSET=EALL, MATERIAL=ELASTIC\n1.\n"
       << "*STEP\n*STATIC\n*BOUNDARY\n";
  for (std::size_t s = 0; s < model.supports.size(); ++s) {
    const Support& sup = model.supports[s];
    if (sup.x && sup.y) {
      deck << "SUPPORT" << s + 1 << ", 1, 2\n";
    } else if (sup.x || sup.y) {
      const int dof = sup.x ? 1 : 2;
      deck << "SUPPORT" << s + 1 << ", " << dof << ", " << dof << "\n";
    }
  }
  bool any_force = false;
  for (const Point& f : model.nodal_forces) any_force = any_force || f.x != 0.0 || f.y != 0.0;
  if (any_force) {
    deck << "*CLOAD\n";
    for (std::size_t i = 0; i < model.nodal_forces.size(); ++i) {
      const Point f = model.nodal_forces[i];
      if (f.x != 0.0) deck << i + 1 << ", 1, " << num(f.x) << "\n";
      if (f.y != 0.0) deck << i + 1 << ", 2, " << num(f.y) << "\n";
    }
  }
  deck << "*NODE FILE\nU\n*EL FILE\nS\n"
       << "*NODE PRINT, NSET=SUPPORTED, TOTALS=ONLY\nRF\n"
       << "*END STEP\n";
  return deck.str();
}

FeSolution read_frd(const std::string& text, std::size_t nodes) {
  FeSolution out;
  out.displacement.assign(nodes, Point{});
  out.stress.assign(nodes, NodalStress{});
  std::vector<bool> have_u(nodes, false), have_s(nodes, false);
  std::istringstream in(text);
  std::string line;
  enum class Block { None, Disp, Stress, Other } block = Block::None;
  bool in_results = false;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.rfind("  100C", 0) == 0) {
      in_results = true;
      block = Block::Other;
      continue;
    }
    if (!in_results) continue;
    if (line.rfind(" -4", 0) == 0) {
      std::istringstream head(line.substr(3));
      std::string name;
      head >> name;
      block = name == "DISP" ? Block::Disp : name == "STRESS" ? Block::Stress : Block::Other;
      continue;
    }
    if (line.rfind(" -3", 0) == 0) {
      in_results = false;
      block = Block::None;
      continue;
    }
    if (line.rfind(" -1", 0) != 0 || (block != Block::Disp && block != Block::Stress)) continue;
    // " -1" + node (I10) + values (E12.5 each): ccx's long format.
    const long node = std::stol(line.substr(3, 10));
    if (node < 1 || static_cast<std::size_t>(node) > nodes) continue;  // ccx's expansion nodes
    const auto i = static_cast<std::size_t>(node - 1);
    if (block == Block::Disp) {
      out.displacement[i] = {field(line, 13, 12), field(line, 25, 12)};
      have_u[i] = true;
    } else {
      // SXX SYY SZZ SXY SYZ SZX
      out.stress[i] = {field(line, 13, 12), field(line, 25, 12), field(line, 37, 12),
                       field(line, 49, 12)};
      have_s[i] = true;
    }
  }
  const auto missing_u = std::count(have_u.begin(), have_u.end(), false);
  const auto missing_s = std::count(have_s.begin(), have_s.end(), false);
  if (missing_u || missing_s) {
    throw std::runtime_error("ccx results: " + std::to_string(missing_u) + " nodes without " +
                             "displacement and " + std::to_string(missing_s) +
                             " without stress in the .frd file");
  }
  return out;
}

Point read_reaction_total(const std::string& dat) {
  std::istringstream in(dat);
  std::string line;
  while (std::getline(in, line)) {
    if (line.find("total force") == std::string::npos) continue;
    // The next non-empty line holds fx fy fz.
    while (std::getline(in, line)) {
      std::istringstream row(line);
      double fx = 0, fy = 0;
      if (row >> fx >> fy) return {fx, fy};
    }
  }
  throw std::runtime_error("ccx results: no total reaction in the .dat file");
}

FeSolution solve_with_calculix(const FeModel& model, const FeTools& tools,
                               const std::filesystem::path& work_dir, const std::string& name,
                               int threads, double timeout_s) {
  const std::filesystem::path inp = work_dir / (name + ".inp");
  {
    std::ofstream out(inp);
    out << calculix_deck(model);
    if (!out) throw FeFailed("cannot write " + inp.string());
  }
  const std::string n = std::to_string(std::max(1, threads));
  ProgramRun run;
  run.program = tools.ccx;
  run.args = {"-i", name};
  run.work_dir = work_dir;
  run.log = work_dir / (name + ".ccx.log");
  run.timeout_s = timeout_s;
  run.env = {{"OMP_NUM_THREADS", n},
             {"CCX_NPROC_EQUATION_SOLVER", n},
             {"CCX_NPROC_STIFFNESS", n},
             {"CCX_NPROC_RESULTS", n}};
  const ProgramResult r = run_program(run);
  const std::string tail = file_tail(run.log, 1500);
  const std::filesystem::path frd = work_dir / (name + ".frd"), dat = work_dir / (name + ".dat");
  if (r.timed_out) {
    throw FeFailed("ccx did not finish within " + num(timeout_s) + " s; its output ends:\n" + tail);
  }
  // ccx may exit with status 0 after an *ERROR: its output says so.
  const std::string log = file_tail(run.log, 1 << 20);
  if (r.exit_status != 0 || log.find("*ERROR") != std::string::npos ||
      !std::filesystem::exists(frd) || !std::filesystem::exists(dat)) {
    throw FeFailed("ccx failed (exit status " + std::to_string(r.exit_status) +
                   "); its output ends:\n" + tail);
  }
  auto read = [](const std::filesystem::path& p) {
    std::ifstream in(p);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
  };
  FeSolution sol;
  try {
    sol = read_frd(read(frd), model.mesh.nodes.size());
    sol.reaction = read_reaction_total(read(dat));
  } catch (const std::exception& e) {
    throw FeFailed(std::string(e.what()) + "; ccx's output ends:\n" + tail);
  }
  for (const Point& f : model.nodal_forces) sol.applied = sol.applied + f;
  sol.wall_s = r.wall_s;
  return sol;
}

}  // namespace gearsph::fe
