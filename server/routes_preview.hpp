#pragma once
// POST /preview: what a job would simulate, before it is submitted.
#include "server/http_types.hpp"
#include "server/services.hpp"

namespace gearsph::server::routes {

Response preview(Services&, Request&);

}  // namespace gearsph::server::routes
