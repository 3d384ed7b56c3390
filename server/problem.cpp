#include "server/problem.hpp"

#include "server/documents.hpp"

namespace gearsph::server::problem {

StringResponse make(const Problem& p) {
  nlohmann::json body = p.extra.is_object() ? p.extra : nlohmann::json::object();
  body["type"] = p.type;
  body["title"] = p.title.empty() ? std::string(http::obsolete_reason(p.status)) : p.title;
  body["status"] = static_cast<unsigned>(p.status);
  if (!p.detail.empty()) body["detail"] = p.detail;
  if (!p.instance.empty()) body["instance"] = p.instance;
  // Invalid UTF-8 from a request (echoed in a detail) must not break the answer.
  return text_response(p.status,
                       body.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n",
                       "application/problem+json");
}

StringResponse plain(http::status status, const std::string& detail, const std::string& instance) {
  Problem p;
  p.status = status;
  p.detail = detail;
  p.instance = instance;
  return make(p);
}

StringResponse no_such_job(const Request& req) {
  Problem p;
  p.status = http::status::not_found;
  p.type = kNoSuchJob;
  p.title = "No such job";
  p.detail = "there is no job " + (req.params.count("id") ? req.param("id") : std::string());
  p.instance = req.path;
  return make(p);
}

StringResponse no_such_process(const Request& req) {
  Problem p;
  p.status = http::status::not_found;
  p.type = kNoSuchProcess;
  p.title = "No such process";
  p.detail = "the only process is " + std::string(kProcessId);
  p.instance = req.path;
  return make(p);
}

StringResponse invalid_parameter(const Request& req, const std::string& detail) {
  Problem p;
  p.status = http::status::bad_request;
  p.type = kInvalidParameter;
  p.title = "Invalid query parameter";
  p.detail = detail;
  p.instance = req.path;
  return make(p);
}

nlohmann::json errors(const std::vector<JobIssue>& issues, const std::string& prefix) {
  nlohmann::json list = nlohmann::json::array();
  for (const JobIssue& i : issues)
    list.push_back({{"pointer", prefix + i.pointer}, {"detail", i.message}});
  return list;
}

}  // namespace gearsph::server::problem
