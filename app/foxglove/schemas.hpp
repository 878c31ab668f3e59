#pragma once
// Foxglove's well-known message schemas (JSON Schema), vendored from the @foxglove/schemas npm
// package by scripts/vendor-foxglove-schemas: a channel that carries one of them by name is drawn
// by Foxglove's panels (3D, Map, Log) without any configuration.

#include <optional>
#include <string_view>

namespace avk::app::foxglove {

extern const char* const kSchemasPackageVersion;

// "foxglove.PoseInFrame", "foxglove.LocationFix", "foxglove.FrameTransform",
// "foxglove.SceneUpdate", "foxglove.Log"; none for any other name.
std::optional<std::string_view> well_known_schema(std::string_view name);

}  // namespace avk::app::foxglove
