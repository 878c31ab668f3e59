#pragma once
// The station's domain types as documents: JSON for the API, the live stream and the command
// line's --format json, CSV for exports. One place, so that a mission report or a prediction has
// the same field names wherever it is read. docs/api.md describes the documents; each resource's
// are in server/serialize/, the values they share in server/serialize/values.hpp.
// Nothing else writes a document: a route or a command parses its input, calls the use case and
// hands the typed result here, so that a field is named and formatted in one place and the HTTP
// answer, the command line's output and the stream's message cannot drift apart.

#include "server/serialize/band.hpp"
#include "server/serialize/ckt.hpp"
#include "server/serialize/comparison.hpp"
#include "server/serialize/currents.hpp"
#include "server/serialize/encounters.hpp"
#include "server/serialize/maneuvers.hpp"
#include "server/serialize/missions.hpp"
#include "server/serialize/models.hpp"
#include "server/serialize/predictions.hpp"
#include "server/serialize/sim.hpp"
#include "server/serialize/station.hpp"
#include "server/serialize/turns.hpp"
#include "server/serialize/values.hpp"
#include "server/serialize/vehicles.hpp"
#include "server/serialize/vocabulary.hpp"
