#include "fe/fe_images.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "render/mesh_image.hpp"
#include "render/plot_image.hpp"
#include "solver/gear/fillet.hpp"

namespace gearsph::fe {

namespace {

render::Polyline polyline(const geometry::Polygon& poly) {
  render::Polyline line;
  for (const Point& p : poly) {
    line.x.push_back(p.x);
    line.y.push_back(p.y);
  }
  line.colour = {30, 30, 30};
  line.width_px = 1.5;
  return line;
}

// The mesh as linear triangles for drawing: each six-node triangle as its
// four corner and mid-side sub-triangles, one value per node.
render::MeshImage field_image(const GearFeResult& r, const std::vector<double>& value) {
  render::MeshImage m;
  for (const Point& p : r.mesh.nodes) {
    m.x.push_back(p.x);
    m.y.push_back(p.y);
  }
  m.value = value;
  for (const auto& e : r.mesh.elements) {
    m.triangles.push_back({e[0], e[3], e[5]});
    m.triangles.push_back({e[3], e[1], e[4]});
    m.triangles.push_back({e[5], e[4], e[2]});
    m.triangles.push_back({e[3], e[4], e[5]});
  }
  m.outlines.push_back(polyline(r.outline));
  for (const geometry::Polygon& hole : r.holes) m.outlines.push_back(polyline(hole));
  m.unit_label = "MPa";
  m.unit_scale = 1e-6;
  return m;
}

// Tooth 0 with both its fillets and a little of the rim above the spaces
// (gear frame: tooth 0 along -y): the window the SPH static check gives as
// tooth0_box_m, so that its field can be drawn in the same one.
render::Window tooth0_window(const GearFeResult& r) {
  double r_tip = 0.0;
  for (const Point& p : r.outline) r_tip = std::max(r_tip, geometry::norm(p));
  const auto [x0, y0, x1, y1] = gear::tooth_window(r.fillets, r_tip);
  return {x0, y0, x1, y1};
}

// The zoomed figures are about as tall as wide, like tooth 0.
constexpr int kZoomWidth = 1100, kZoomHeight = 1000;

void write(const std::filesystem::path& path, const std::vector<unsigned char>& png) {
  render::write_png(path, png);
}

}  // namespace

std::vector<std::string> write_fe_images(const std::vector<GearFeResult>& meshes,
                                         const std::filesystem::path& dir,
                                         const std::string& title) {
  std::vector<std::string> files;
  if (meshes.empty()) return files;
  const GearFeResult& r = meshes.back();
  std::vector<double> vm, s1;
  double vm_max = 0.0;
  for (const NodalStress& s : r.solution.stress) {
    vm.push_back(s.von_mises());
    s1.push_back(s.max_principal());
    vm_max = std::max(vm_max, vm.back());
  }
  // Colours for the root: up to a quarter above the larger fillet peak; the
  // contact zone under the load goes beyond and takes the end colour.
  const double fillet_max =
      std::max(std::abs(r.stress.tension.stress_Pa), std::abs(r.stress.compression.stress_Pa));
  const double cap = root_image_range_Pa(r)[1];
  // The load's contact zone goes beyond the range (its end colour).
  const std::string off_scale = vm_max > cap ? " (load zone off scale)" : "";
  const render::Window zoom = tooth0_window(r);
  auto zoomed = [&zoom](render::MeshImage m) {
    m.zoom = zoom;
    m.width = kZoomWidth;
    m.height = kZoomHeight;
    return m;
  };

  render::MeshImage von_mises = field_image(r, vm);
  von_mises.field_label = "von Mises stress" + off_scale;
  von_mises.vmin = 0.0;
  von_mises.vmax = cap;
  von_mises.title = "FE von Mises, " + title;
  write(dir / "fe_von_mises.png", render::render_mesh_png(von_mises));
  write(dir / "fe_von_mises_tooth0.png", render::render_mesh_png(zoomed(von_mises)));

  render::MeshImage principal = field_image(r, s1);
  principal.field_label = "largest principal stress" + off_scale;
  principal.diverging = true;
  principal.vmin = -cap;
  principal.vmax = cap;
  principal.title = "FE largest principal stress, " + title;
  write(dir / "fe_max_principal.png", render::render_mesh_png(principal));
  write(dir / "fe_max_principal_tooth0.png", render::render_mesh_png(zoomed(principal)));

  // The mesh at the root: element edges (through the mid-side nodes) over
  // the von Mises field in bands.
  render::MeshImage mesh = zoomed(von_mises);
  mesh.bands = 10;
  mesh.edge_width_px = 0.8;
  for (const auto& e : r.mesh.elements) {
    for (int k = 0; k < 3; ++k) {
      mesh.edges.push_back({e[k], e[3 + k]});
      mesh.edges.push_back({e[3 + k], e[(k + 1) % 3]});
    }
  }
  char mesh_title[96];
  std::snprintf(mesh_title, sizeof mesh_title, "FE mesh: %.3g mm at the fillets, %zu elements",
                1e3 * r.sizes.fillet, r.mesh.elements.size());
  mesh.title = mesh_title;
  write(dir / "fe_mesh_tooth0.png", render::render_mesh_png(mesh));
  files.insert(files.end(), {"fe_von_mises.png", "fe_von_mises_tooth0.png", "fe_max_principal.png",
                             "fe_max_principal_tooth0.png", "fe_mesh_tooth0.png"});

  // Fillet stress against arc length, every mesh.
  render::Plot plot;
  plot.title = "FE stress along tooth 0's fillets, " + title;
  plot.x_label = "arc length from the space centre [mm]";
  plot.y_label = "stress [MPa]";
  for (std::size_t k = 0; k < meshes.size(); ++k) {
    const GearFeResult& m = meshes[k];
    char label[80];
    render::Series t, c;
    std::snprintf(label, sizeof label, "tension, \u03c3\u2081 (%.3g mm mesh)",
                  1e3 * m.sizes.fillet);
    t.name = label;
    std::snprintf(label, sizeof label, "compression, \u03c3\u2083 (%.3g mm mesh)",
                  1e3 * m.sizes.fillet);
    c.name = label;
    for (std::size_t i = 0; i < m.fillets.tension.size(); ++i) {
      t.x.push_back(1e3 * m.fillets.tension.arc[i]);
      t.y.push_back(1e-6 * m.stress.tension_curve[i]);
    }
    for (std::size_t i = 0; i < m.fillets.compression.size(); ++i) {
      c.x.push_back(1e3 * m.fillets.compression.arc[i]);
      c.y.push_back(1e-6 * m.stress.compression_curve[i]);
    }
    plot.series.push_back(t);
    plot.series.push_back(c);
  }
  // ISO's 30-degree point on the tension fillet.
  const gear::FilletCurve& f = r.fillets.tension;
  const double arc30 = f.arc[f.i30] + f.f30 * (f.arc[f.i30 + 1] - f.arc[f.i30]);
  render::Series iso;
  iso.name = "ISO 30-degree point";
  iso.x = {1e3 * arc30, 1e3 * arc30};
  iso.y = {-1e-6 * fillet_max, 1e-6 * fillet_max};
  iso.colour = render::Rgb8{120, 120, 120};
  plot.series.push_back(iso);
  // Room above the curves for the legend (top right, one row a series).
  const double lo = -1.1 * std::abs(r.stress.compression.stress_Pa) * 1e-6;
  const double top = 1.1 * std::abs(r.stress.tension.stress_Pa) * 1e-6;
  const double legend_share = std::min(0.6, 0.07 * static_cast<double>(plot.series.size()));
  plot.y_range = render::Range{lo, lo + (top - lo) / (1.0 - legend_share)};
  write(dir / "fe_fillet_curves.png", render::render_plot_png(plot));
  files.push_back("fe_fillet_curves.png");
  return files;
}

}  // namespace gearsph::fe
