#pragma once
// The study works on the loader's Record (imunoise/load/record.hpp).
#include "imunoise/load/record.hpp"

namespace imunoise::study {

using imunoise::Record;
using imunoise::is_gyro;
using imunoise::table_notes;
using imunoise::unit_label;

}  // namespace imunoise::study
