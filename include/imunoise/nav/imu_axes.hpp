#pragma once
// Which channel of an IMU is which axis (x north, y east, z down): by name when every name
// says a distinct axis (a word x, y or z of its own: gyro_x_dps, w_RS_S_y; or the last letter:
// az), otherwise in the order given. Shared by the study and `imunoise nav --from report.json`.
#include <array>
#include <span>
#include <string>
#include <string_view>

namespace imunoise::nav {

/// 0, 1, 2 for x, y, z; -1 when the name says no axis.
int axis_of_name(std::string_view name);

/// The index (into `names`) of the channel on each axis, -1 for none; at most three channels
/// are placed (by order, the first three).
std::array<int, 3> channels_on_axes(std::span<const std::string> names);

}  // namespace imunoise::nav
