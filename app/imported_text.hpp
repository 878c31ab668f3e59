#pragma once
// The free text a mission brings from a file (an MCAP recording, an alog): its name, its
// vehicle's id and kind, the reasons and event messages it was stored with. It is bounded like
// the station's own input before anything is stored: a name is listed with every mission, and
// one of 900 kB made every list 900 kB. The limits (docs/api.md, "Text limits"):

#include <cstddef>

#include "app/result.hpp"
#include "store/store.hpp"

namespace avk::app {

inline constexpr std::size_t kMaxVehicleKindBytes = 64;
inline constexpr std::size_t kMaxReasonBytes = 1024;  // a mission's status reason, a turn's reason
inline constexpr std::size_t kMaxEventKindBytes = 64;
inline constexpr std::size_t kMaxEventMessageBytes = 4096;

// Done, or invalid_argument (field "file") naming the record and the field that is too long (or,
// for the vehicle id, what else is wrong with it).
Status check_imported_text(const store::MissionImport& d);

}  // namespace avk::app
