#include "imunoise/nav/imu_axes.hpp"

#include <algorithm>
#include <cctype>

namespace imunoise::nav {
namespace {

int axis_letter(char c) {
  c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return c == 'x' ? 0 : c == 'y' ? 1 : c == 'z' ? 2 : -1;
}

}  // namespace

int axis_of_name(std::string_view name) {
  int found = -1;
  std::size_t words = 0;
  for (std::size_t i = 0; i < name.size();) {
    std::size_t j = i;
    while (j < name.size() && std::isalnum(static_cast<unsigned char>(name[j]))) ++j;
    if (j == i + 1 && axis_letter(name[i]) >= 0) {
      found = axis_letter(name[i]);
      ++words;
    }
    i = std::max(j, i) + 1;
  }
  if (words == 1) return found;
  return name.empty() ? -1 : axis_letter(name.back());
}

std::array<int, 3> channels_on_axes(std::span<const std::string> names) {
  std::array<int, 3> axes{-1, -1, -1};
  bool by_name = names.size() <= 3;
  for (std::size_t i = 0; by_name && i < names.size(); ++i) {
    const int a = axis_of_name(names[i]);
    if (a < 0 || axes[static_cast<std::size_t>(a)] >= 0) {
      by_name = false;
    } else {
      axes[static_cast<std::size_t>(a)] = static_cast<int>(i);
    }
  }
  if (by_name) return axes;
  axes = {-1, -1, -1};
  for (std::size_t i = 0; i < names.size() && i < 3; ++i) axes[i] = static_cast<int>(i);
  return axes;
}

}  // namespace imunoise::nav
