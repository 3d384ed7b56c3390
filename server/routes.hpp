#pragma once
// The request handlers: each maps a request to a response. The table that
// connects them to methods and paths is in router.cpp.
#include "server/http_types.hpp"
#include "server/services.hpp"

namespace gearsph::server::routes {

// routes_service.cpp: the service's description of itself
Response landing(Services&, Request&);
Response api_definition(Services&, Request&);  // GET /api: the OpenAPI document
Response conformance(Services&, Request&);
Response health(Services&, Request&);
Response metrics(Services&, Request&);
Response schema(Services&, Request&);
Response processes(Services&, Request&);
Response process(Services&, Request&);

// routes_jobs.cpp
Response execute(Services&, Request&);  // POST /processes/{process}/execution and POST /jobs
Response list_jobs(Services&, Request&);
Response job(Services&, Request&);
Response dismiss_job(Services&, Request&);
Response results(Services&, Request&);

// routes_files.cpp
Response files(Services&, Request&);
Response file(Services&, Request&);
Response image(Services&, Request&);

// routes_events.cpp
Response job_events(Services&, Request&);
Response all_events(Services&, Request&);

// routes_login.cpp: the cookie a browser carries instead of the token
Response login_state(Services&, Request&);
Response login(Services&, Request&);
Response logout(Services&, Request&);

// routes_studies.cpp
Response create_study(Services&, Request&);
Response study(Services&, Request&);

}  // namespace gearsph::server::routes
