#pragma once
// The one mapping of the use cases' errors to HTTP: status and problem+json.
//   not_found 404 · invalid_argument 400 for a query parameter, 422 for a field of a request
//   document · conflict 409 · not_authorised 403 · unsupported 422 · internal 500

#include "app/result.hpp"
#include "server/api_types.hpp"

namespace avk::server {

// document: the error is about the request's body (a POST), not its query parameters.
ApiResponse problem_of(const app::Error& e, bool document);

}  // namespace avk::server
