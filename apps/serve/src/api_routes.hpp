// api_routes.hpp — the JSON API's endpoints (docs/serve.md) on an httplib::Server.
#pragma once
#include <httplib.h>

#include "server_state.hpp"

namespace knit::serve {

void addApiRoutes(httplib::Server& http, ServerState& state);

}  // namespace knit::serve
