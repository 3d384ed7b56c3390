#pragma once
// The API definition: an OpenAPI 3.0 document of every endpoint, written by
// hand in server/openapi.json and compiled in; served at /api (linked from
// the landing page as service-desc). A test holds it to the router's table.
#include <string_view>

namespace gearsph::server {

std::string_view openapi_document();

}  // namespace gearsph::server
