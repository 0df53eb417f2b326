// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// cellforge's version, semantic from 0.2.0 on: before 1.0 a minor release may break the API
/// (CHANGELOG.md says how to migrate; renamed names keep a deprecated alias for one minor
/// version), a patch release never does. CMakeLists.txt reads the numbers from this file.

#define CELLFORGE_VERSION_MAJOR 0
#define CELLFORGE_VERSION_MINOR 8
#define CELLFORGE_VERSION_PATCH 0
#define CELLFORGE_VERSION_STRING "0.8.0"

namespace cellforge {

/// The version of the headers included, for run-time checks and logs. O(1).
struct version_info {
  int major, minor, patch;
  const char* string;
};
inline constexpr version_info version{CELLFORGE_VERSION_MAJOR, CELLFORGE_VERSION_MINOR,
                                      CELLFORGE_VERSION_PATCH, CELLFORGE_VERSION_STRING};

}  // namespace cellforge
