// gearsph fe JOB.json --out DIR: the finite-element check of a quasi-static
// rack_pinion job (fe/fe_check.hpp), optionally beside a finished SPH run.
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "apps/gearsph/cli.hpp"
#include "fe/external_program.hpp"
#include "fe/fe_check.hpp"
#include "solver/job/job.hpp"
#include "solver/run/execute.hpp"

namespace gearsph::cli {

namespace {

double positive_number(const std::string& name, const std::string& text) {
  try {
    std::size_t used = 0;
    const double v = std::stod(text, &used);
    if (used == text.size() && v > 0.0) return v;
  } catch (const std::exception&) {
  }
  throw std::invalid_argument("--" + name + " takes a positive number, not '" + text + "'");
}

std::vector<double> sizes_mm(const std::string& text) {
  std::vector<double> out;
  std::stringstream list(text);
  std::string item;
  while (std::getline(list, item, ','))
    out.push_back(1e-3 * positive_number("fillet-sizes-mm", item));
  if (out.empty()) throw std::invalid_argument("--fillet-sizes-mm needs at least one size");
  return out;
}

void print_report(const nlohmann::json& s) {
  const nlohmann::json& load = s.at("load");
  std::printf(
      "%s: F_n = %.1f N (F_t %.1f N) at r = %.3f mm on %s; %s\n",
      s.at("job").get<std::string>().c_str(), load.at("normal_force_N").get<double>(),
      load.at("tangential_force_N").get<double>(), 1e3 * load.at("load_radius_m").get<double>(),
      load.at("flank").get<std::string>().c_str(), load.at("source").get<std::string>().c_str());
  std::printf("%9s %7s %8s %13s %13s %13s %11s %8s\n", "fillet", "nodes", "elements",
              "tension peak", "at 30 deg", "compression", "reaction", "time");
  for (const nlohmann::json& m : s.at("meshes")) {
    std::printf("%6.3f mm %7zu %8zu %9.2f MPa %9.2f MPa %9.2f MPa %11.2e %6.1f s\n",
                1e3 * m.at("fillet_size_m").get<double>(), m.at("nodes").get<std::size_t>(),
                m.at("elements").get<std::size_t>(),
                1e-6 * m.at("fillet_tension_peak_Pa").get<double>(),
                1e-6 * m.at("fillet_stress_at_iso30_Pa").get<double>(),
                1e-6 * m.at("fillet_compression_peak_Pa").get<double>(),
                m.at("reaction_imbalance").get<double>(),
                m.at("mesh_s").get<double>() + m.at("solve_s").get<double>());
  }
  if (s.contains("coarse_fine_difference")) {
    const nlohmann::json& d = s.at("coarse_fine_difference");
    std::printf(
        "coarse against fine: tension peak %+.2f %%, at 30 deg %+.2f %%, compression "
        "%+.2f %%\n",
        100.0 * d.at("fillet_tension_peak_Pa").at("relative_difference").get<double>(),
        100.0 * d.at("fillet_stress_at_iso30_Pa").at("relative_difference").get<double>(),
        100.0 * d.at("fillet_compression_peak_Pa").at("relative_difference").get<double>());
  }
  std::printf(
      "pinion compliance at the load (tooth, rim and the pinion's Hertz indentation, from the "
      "held radius): %.4f um mm/N\n",
      s.at("pinion_compliance_at_load_um_mm_per_N").get<double>());
  std::printf("rack compliance at the load (tooth and back, from the rack's mean): %.4f um mm/N\n",
              s.at("rack_compliance_um_mm_per_N").get<double>());
  std::printf(
      "at the contact centres: pinion %.4f, rack %.4f um mm/N; the pair's stiffness %.2f N/(mm "
      "um) (%.2f from the work-conjugate means)\n",
      s.at("pinion_compliance_at_centre_um_mm_per_N").get<double>(),
      s.at("rack_compliance_at_centre_um_mm_per_N").get<double>(),
      s.at("pair_mesh_stiffness_N_per_mm_um").get<double>(),
      s.at("pair_mesh_stiffness_work_conjugate_N_per_mm_um").get<double>());
  const nlohmann::json& iso = s.at("iso_6336_3");
  std::printf(
      "ISO 6336-3 sigma_F0 = %.2f MPa (Y_F %.3f, Y_S %.3f): FE peak / sigma_F0 = %.3f, "
      "FE at 30 deg / sigma_F0 = %.3f\n",
      1e-6 * iso.at("sigma_F0_Pa").get<double>(), iso.at("Y_F").get<double>(),
      iso.at("Y_S").get<double>(), iso.at("fillet_tension_peak_over_sigma_F0").get<double>(),
      iso.at("fillet_stress_at_iso30_over_sigma_F0").get<double>());
}

}  // namespace

int cmd_fe(Args& args) {
  const auto out = args.option("out");
  fe::FeCheckOptions o;
  if (const auto v = args.option("fillet-sizes-mm")) o.fillet_sizes_m = sizes_mm(*v);
  o.threads = std::max(1, args.integer("threads", 1));
  if (const auto v = args.option("timeout-s")) o.timeout_s = positive_number("timeout-s", *v);
  if (const auto v = args.option("rim-depth-mm")) {
    o.rim_depth_m = 1e-3 * positive_number("rim-depth-mm", *v);
  }
  if (const auto v = args.option("teeth")) {
    if (*v == "all") {
      o.whole_gear = true;
    } else {
      const int n = static_cast<int>(positive_number("teeth", *v));
      if (n % 2 == 0) throw std::invalid_argument("--teeth takes an odd number or all");
      o.teeth = std::pair{-(n / 2), n / 2};
    }
  }
  const auto compare = args.option("compare");
  o.keep_model_files = args.flag("keep-model-files");
  o.images = !args.flag("no-images");
  const bool quiet = args.flag("quiet");
  const auto pos = args.positional();
  if (pos.size() != 1 || !out) {
    throw std::invalid_argument("usage: gearsph fe JOB.json --out DIR (gearsph fe --help)");
  }
  if (!quiet)
    o.log = [](const std::string& line) { std::fprintf(stderr, "gearsph fe: %s\n", line.c_str()); };
  nlohmann::json sph;
  if (compare) {
    sph = nlohmann::json::parse(read_file(*compare + "/summary.json"));
    if (!sph.contains("analysis") || !sph["analysis"].contains("static_check")) {
      throw std::invalid_argument(
          "--compare: " + *compare +
          "/summary.json has no analysis.static_check (not a quasi-static rack_pinion run)");
    }
    // The SPH run's load and structure (teeth, held rim), unless the
    // command line gives its own.
    const auto teeth = o.teeth;
    const bool whole = o.whole_gear;
    const auto rim = o.rim_depth_m;
    o.whole_gear = false;
    fe::model_the_sph_run(sph, *compare + "/summary.json", o);
    if (teeth || whole) {
      o.teeth = teeth;
      o.whole_gear = whole;
    }
    if (rim) o.rim_depth_m = rim;
  }
  nlohmann::json summary;
  try {
    summary = fe::run_fe_check(validate_job(parse_job_text(read_file(pos[0]))), *out, o);
  } catch (const InvalidJob& e) {
    std::fprintf(stderr, "gearsph fe: %s is not a job the FE check can model:\n", pos[0].c_str());
    for (const JobIssue& i : e.issues) {
      std::fprintf(stderr, "  %s: %s\n", i.pointer.empty() ? "(document)" : i.pointer.c_str(),
                   i.message.c_str());
    }
    return 2;
  } catch (const fe::FeUnavailable& e) {
    std::fprintf(stderr, "gearsph fe: %s\n", e.what());
    return 5;
  } catch (const fe::FeFailed& e) {
    std::fprintf(stderr, "gearsph fe: %s\n", e.what());
    return 1;
  }
  print_report(summary);
  if (compare) {
    const nlohmann::json block = fe::fe_comparison(sph, summary);
    write_file_atomic(std::filesystem::path(*out) / "fe_comparison.json", block.dump(2) + "\n");
    std::printf("SPH against FE (%s):\n", block.at("status").get<std::string>().c_str());
    for (const std::string& key : fe::fillet_keys()) {
      const nlohmann::json& e = block.at(key);
      if (e.at("sph").is_null()) {
        std::printf("  %-30s sph -, fe %.6g\n", key.c_str(), e.at("fe").get<double>());
      } else {
        std::printf("  %-30s sph %.6g, fe %.6g, error %+.2f %%\n", key.c_str(),
                    e.at("sph").get<double>(), e.at("fe").get<double>(),
                    100.0 * e.at("error").get<double>());
      }
    }
  }
  std::printf("wrote %s/fe_summary.json", out->c_str());
  for (const auto& f : summary.at("files")) {
    if (f != "fe_summary.json") std::printf(", %s", f.get<std::string>().c_str());
  }
  std::printf("%s in %.1f s\n", compare ? ", fe_comparison.json" : "",
              summary.at("wall_s").get<double>());
  return 0;
}

}  // namespace gearsph::cli
