#include "server/study.hpp"

#include <set>

namespace gearsph::server {

namespace {

constexpr std::size_t kMaxAxes = 8;
constexpr std::size_t kMaxArrayItems = 8;  // longer arrays are not spread over columns

[[noreturn]] void refuse(const std::string& pointer, const std::string& message) {
  throw InvalidJob({{pointer, message}});
}

}  // namespace

StudySpec parse_study(const nlohmann::json& body, std::int64_t max_jobs) {
  if (!body.is_object()) refuse("", "a study is an object with base and axes");
  std::vector<JobIssue> issues;
  for (const auto& [key, value] : body.items()) {
    if (key != "name" && key != "base" && key != "axes") {
      issues.push_back({"/" + key, "is not a field of a study (name, base, axes)"});
    }
  }
  StudySpec spec;
  if (body.contains("name")) {
    if (!body["name"].is_string() || body["name"].get<std::string>().empty() ||
        body["name"].get<std::string>().size() > 100) {
      issues.push_back({"/name", "is a string of 1 to 100 characters"});
    } else {
      spec.name = body["name"].get<std::string>();
    }
  }
  if (!body.contains("base") || !body["base"].is_object()) {
    issues.push_back({"/base", "is required: the job every point of the study starts from"});
  } else {
    spec.base = body["base"];
  }
  if (!body.contains("axes") || !body["axes"].is_array() || body["axes"].empty() ||
      body["axes"].size() > kMaxAxes) {
    issues.push_back({"/axes", "is required: a list of 1 to " + std::to_string(kMaxAxes) +
                                   " axes, each {\"pointer\": \"/a/b\", \"values\": [...]}"});
  } else {
    std::set<std::string> seen;
    double count = 1.0;
    for (std::size_t k = 0; k < body["axes"].size(); ++k) {
      const auto& a = body["axes"][k];
      const std::string at = "/axes/" + std::to_string(k);
      if (!a.is_object()) {
        issues.push_back({at, "is an object {\"pointer\": ..., \"values\": [...]}"});
        continue;
      }
      for (const auto& [key, value] : a.items()) {
        if (key != "pointer" && key != "values") {
          issues.push_back({at + "/" + key, "is not a field of an axis (pointer, values)"});
        }
      }
      StudyAxis axis;
      if (!a.contains("pointer") || !a["pointer"].is_string()) {
        issues.push_back(
            {at + "/pointer", "is required: a JSON pointer into the job, e.g. /time/end_s"});
      } else {
        axis.pointer = a["pointer"].get<std::string>();
        try {
          const nlohmann::json::json_pointer p(axis.pointer);
          if (p.empty()) {
            issues.push_back({at + "/pointer", "must point into the job, not at all of it"});
          } else if (p.to_string() == "/name" || p.to_string().rfind("/name/", 0) == 0) {
            // N9: each job's name is the study's (its name and the job's
            // number, routes_studies.cpp); the axis would vary no physics.
            issues.push_back(
                {at + "/pointer",
                 "points at the job's name, which a study sets itself (the study's name and the "
                 "job's number) and which varies nothing in the run; vary a field of the job, "
                 "e.g. /time/end_s, and name the study with its own \"name\""});
          }
        } catch (const nlohmann::json::exception&) {
          issues.push_back({at + "/pointer", "is not a JSON pointer (RFC 6901), e.g. /time/end_s"});
        }
        if (!seen.insert(axis.pointer).second) {
          issues.push_back({at + "/pointer", "repeats the pointer of another axis"});
        }
      }
      if (!a.contains("values") || !a["values"].is_array() || a["values"].empty()) {
        issues.push_back({at + "/values", "is required: a non-empty list of values"});
      } else {
        for (const auto& v : a["values"]) axis.values.push_back(v);
        count *= double(axis.values.size());
      }
      spec.axes.push_back(std::move(axis));
    }
    if (count > double(max_jobs)) {
      issues.push_back({"/axes", "would make " + std::to_string(static_cast<long long>(count)) +
                                     " jobs; a study makes at most " + std::to_string(max_jobs)});
    }
  }
  if (!issues.empty()) throw InvalidJob(issues);
  return spec;
}

std::vector<StudyPoint> expand_study(const StudySpec& spec) {
  std::vector<StudyPoint> points;
  std::vector<std::size_t> index(spec.axes.size(), 0);
  for (;;) {
    StudyPoint p;
    p.job = spec.base;
    p.parameters = nlohmann::json::object();
    p.value_index = index;
    for (std::size_t k = 0; k < spec.axes.size(); ++k) {
      const StudyAxis& axis = spec.axes[k];
      const nlohmann::json& value = axis.values[index[k]];
      try {
        p.job[nlohmann::json::json_pointer(axis.pointer)] = value;
      } catch (const nlohmann::json::exception&) {
        refuse("/axes/" + std::to_string(k) + "/pointer",
               "cannot be set in the base job: it runs through a value that is not an object");
      }
      p.parameters[axis.pointer] = value;
    }
    points.push_back(std::move(p));
    // Next index, the last axis fastest.
    std::size_t k = spec.axes.size();
    while (k > 0) {
      --k;
      if (++index[k] < spec.axes[k].values.size()) break;
      index[k] = 0;
      if (k == 0) return points;
    }
    if (spec.axes.empty()) return points;
  }
}

void flatten_scalars(const nlohmann::json& j, const std::string& prefix, StudyRow& row) {
  if (j.is_object()) {
    for (const auto& [key, value] : j.items()) {
      flatten_scalars(value, prefix.empty() ? key : prefix + "." + key, row);
    }
  } else if (j.is_array()) {
    if (j.size() > kMaxArrayItems) return;
    for (std::size_t i = 0; i < j.size(); ++i) {
      flatten_scalars(j[i], prefix + "[" + std::to_string(i) + "]", row);
    }
  } else {
    row.emplace_back(prefix, j);
  }
}

StudyTable study_table(const std::vector<StudyRow>& rows) {
  StudyTable t;
  std::set<std::string> known;
  for (const StudyRow& r : rows) {
    nlohmann::json obj = nlohmann::json::object();
    for (const auto& [column, value] : r) {
      if (known.insert(column).second) t.columns.push_back(column);
      obj[column] = value;
    }
    t.rows.push_back(std::move(obj));
  }
  return t;
}

std::string to_csv(const StudyTable& table) {
  auto cell = [](const std::string& s) {
    if (s.find_first_of(",\"\r\n") == std::string::npos) return s;
    std::string q = "\"";
    for (char c : s) {
      if (c == '"') q += '"';
      q += c;
    }
    return q + "\"";
  };
  std::string out;
  for (std::size_t i = 0; i < table.columns.size(); ++i) {
    if (i) out += ',';
    out += cell(table.columns[i]);
  }
  out += "\n";
  for (const nlohmann::json& row : table.rows) {
    for (std::size_t i = 0; i < table.columns.size(); ++i) {
      if (i) out += ",";
      const auto it = row.find(table.columns[i]);
      if (it == row.end() || it->is_null()) continue;
      out += cell(it->is_string() ? it->get<std::string>() : it->dump());
    }
    out += "\n";
  }
  return out;
}

}  // namespace gearsph::server
