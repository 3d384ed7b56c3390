#include "render/fillet_plot.hpp"

#include <filesystem>
#include <fstream>
#include <mutex>

#include "render/plot_image.hpp"
#include "solver/run/execute.hpp"

namespace gearsph::render {

namespace {

Series curve(const std::string& name, const nlohmann::json& arc, const nlohmann::json& stress,
             std::optional<Rgb8> colour) {
  Series s;
  s.name = name;
  s.colour = colour;
  for (std::size_t i = 0; i < arc.size() && i < stress.size(); ++i) {
    s.x.push_back(1e3 * arc[i].get<double>());
    s.y.push_back(1e-6 * stress[i].get<double>());
  }
  return s;
}

}  // namespace

std::vector<unsigned char> fillet_plot_png(const nlohmann::json& sc, const nlohmann::json& fe) {
  const nlohmann::json& c = sc.at("fillet_curves");
  Plot plot;
  plot.title = "Tooth 0 fillets, load at r = " +
               std::to_string(1e3 * sc.value("load_radius_m", 0.0)).substr(0, 5) + " mm";
  plot.x_label = "arc length from the middle of the tooth space [mm]";
  plot.y_label = "stress on the fillet [MPa]";
  const Rgb8 red{200, 40, 40}, blue{40, 80, 200}, dark_red{110, 0, 0}, dark_blue{0, 20, 110};
  plot.series.push_back(curve("SPH tension fillet, \u03c3\u2081", c.at("tension").at("arc_m"),
                              c.at("tension").at("sigma1_Pa"), red));
  plot.series.push_back(curve("SPH compression fillet, \u03c3\u2083",
                              c.at("compression").at("arc_m"), c.at("compression").at("sigma3_Pa"),
                              blue));
  if (fe.is_object() && fe.contains("meshes") && !fe.at("meshes").empty()) {
    const nlohmann::json& m = fe.at("meshes").back();  // the finest: the reference
    plot.series.push_back(
        curve("FE tension fillet", m.at("arc_m"), m.at("tension_sigma1_Pa"), dark_red));
    plot.series.push_back(
        curve("FE compression fillet", m.at("arc_m"), m.at("compression_sigma3_Pa"), dark_blue));
  }
  return render_plot_png(plot);
}

void register_fillet_plot() {
  static std::once_flag once;
  std::call_once(once, [] {
    register_summary_addition([](const PreparedJob&, const RunResult&,
                                 const std::filesystem::path& dir, const ExecuteOptions&,
                                 nlohmann::json& summary) {
      if (!summary.contains("analysis") || !summary["analysis"].contains("static_check")) return;
      nlohmann::json& sc = summary["analysis"]["static_check"];
      if (!sc.contains("fillet_curves")) return;
      nlohmann::json fe;
      std::ifstream in(dir / "fe_fillet_curves.json");
      if (in) fe = nlohmann::json::parse(in, nullptr, false);
      const std::vector<unsigned char> png =
          fillet_plot_png(sc, fe.is_discarded() ? nlohmann::json() : fe);
      std::ofstream out(dir / "fillet_curves.png", std::ios::binary);
      out.write(reinterpret_cast<const char*>(png.data()),
                static_cast<std::streamsize>(png.size()));
      sc["fillet_plot"] = "fillet_curves.png";
    });
  });
}

}  // namespace gearsph::render
