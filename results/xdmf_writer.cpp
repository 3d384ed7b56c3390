#include "results/xdmf_writer.hpp"

#include <algorithm>
#include <cstdio>

#include "results/results_layout.hpp"
#include "solver/run/execute.hpp"

namespace gearsph::results {

namespace {

// Full precision, so that ParaView's time values equal /frames/time.
std::string number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

// A HyperSlab DataItem selecting row `frame` of an [F x N (x 3)] dataset.
std::string slab(const FieldSpec& f, std::size_t frame, std::size_t frames, std::size_t n,
                 const std::string& h5_name) {
  const std::string N = std::to_string(n), k = std::to_string(frame);
  const bool vec = f.components == 3;
  const std::string row = vec ? N + " 3" : N;
  const std::string select = vec ? k + " 0 0 1 1 1 1 " + N + " 3" : k + " 0 1 1 1 " + N;
  const std::string type =
      f.integer ? R"(NumberType="Int" Precision="4")" : R"(NumberType="Float" Precision="8")";
  std::string s;
  s += "     <DataItem ItemType=\"HyperSlab\" Dimensions=\"" + row + "\">\n";
  s += "      <DataItem Dimensions=\"3 " + std::string(vec ? "3" : "2") + "\" Format=\"XML\">" +
       select + "</DataItem>\n";
  s += "      <DataItem Dimensions=\"" + std::to_string(frames) + " " + row + "\" " + type +
       " Format=\"HDF\">" + h5_name + ":/frames/" + f.name + "</DataItem>\n";
  s += "     </DataItem>\n";
  return s;
}

std::string grid(std::size_t frame, double time, std::size_t frames, std::size_t n,
                 const std::string& h5_name) {
  char name[32];
  std::snprintf(name, sizeof name, "frame_%06zu", frame);
  std::string s = "   <Grid Name=\"" + std::string(name) + "\" GridType=\"Uniform\">\n";
  s += "    <Time Value=\"" + number(time) + "\"/>\n";
  s += "    <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"" + std::to_string(n) +
       "\" NodesPerElement=\"1\"/>\n";
  for (const FieldSpec& f : kFrameFields) {
    const std::string field = f.name;
    if (field == "position") {
      s += "    <Geometry GeometryType=\"XYZ\">\n" + slab(f, frame, frames, n, h5_name) +
           "    </Geometry>\n";
      continue;
    }
    s += "    <Attribute Name=\"" + field + "\" AttributeType=\"" +
         (f.components == 3 ? "Vector" : "Scalar") + "\" Center=\"Node\">\n" +
         slab(f, frame, frames, n, h5_name) + "    </Attribute>\n";
  }
  return s + "   </Grid>\n";
}

}  // namespace

std::string xdmf_document(const std::string& h5_name, std::size_t particles,
                          const std::vector<double>& times, std::size_t dataset_frames) {
  // Datasets grow when more frames come than planned; ParaView's reader
  // accepts a declared size smaller than the dataset's.
  const std::size_t rows = std::max(dataset_frames, times.size());
  std::string s =
      "<?xml version=\"1.0\" ?>\n"
      "<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n"
      "<Xdmf Version=\"2.0\">\n"
      " <Domain>\n"
      "  <Grid Name=\"particles\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (std::size_t k = 0; k < times.size(); ++k) {
    s += grid(k, times[k], rows, particles, h5_name);
  }
  return s + "  </Grid>\n </Domain>\n</Xdmf>\n";
}

XdmfWriter::XdmfWriter(std::filesystem::path path, std::string h5_name, std::size_t particles,
                       std::size_t dataset_frames)
    : path_(std::move(path)),
      h5_name_(std::move(h5_name)),
      particles_(particles),
      dataset_frames_(dataset_frames) {}

void XdmfWriter::write() {
  const auto start = Clock::now();
  write_file_atomic(path_, xdmf_document(h5_name_, particles_, times_, dataset_frames_));
  last_write_ = Clock::now();
  last_duration_ = last_write_ - start;
  written_ = true;
}

void XdmfWriter::write_throttled() {
  constexpr int kSpacing = 50;
  const Clock::duration wait =
      std::max<Clock::duration>(std::chrono::seconds(1), kSpacing * last_duration_);
  if (!written_ || Clock::now() - last_write_ >= wait) write();
}

}  // namespace gearsph::results
