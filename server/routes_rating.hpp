#pragma once
// POST /rating: a rating document (schemas/rating.schema.json) in, its ISO
// 6336 verdict out, at once: nothing is stored or queued.
#include "server/http_types.hpp"
#include "server/services.hpp"

namespace gearsph::server::routes {

Response rating(Services&, Request&);

}  // namespace gearsph::server::routes
