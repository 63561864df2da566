#!/usr/bin/env Rscript
# Converts the six ADIS16405 recordings of the R data package `imudata` (SMAC-Group/imudata on
# GitHub, CC BY-NC-SA 4.0; data from the Department of Geomatics Engineering, University of
# Calgary) into the CSV layout the real-record tests read, outside the repository (the licence
# keeps the data out of it):
#
#   Rscript scripts/imudata_to_csv.R <folder with adis_16405_imu1..6.rda> <output folder>
#   IMUNOISE_SHARED_DATA=<output folder> build/default/tests/imunoise_test_fit --gtest_filter='RealAdis16405.*'
#
# Needs only base R (Debian: r-base-core). Each file: a 1e6 x 6 matrix at 100 Hz, gyros in
# deg/s, accelerometers in g (the package's own documentation); its unit 2 is the record of
# ../shared/data.
args <- commandArgs(trailingOnly = TRUE)
if (length(args) != 2) stop("usage: imudata_to_csv.R <rda folder> <output folder>")
dir.create(args[2], showWarnings = FALSE, recursive = TRUE)
header <- c("gyro_x_dps", "gyro_y_dps", "gyro_z_dps", "accel_x_g", "accel_y_g", "accel_z_g")
for (i in 1:6) {
  source_file <- file.path(args[1], sprintf("adis_16405_imu%d.rda", i))
  if (!file.exists(source_file)) stop(paste("missing", source_file))
  env <- new.env()
  name <- load(source_file, envir = env)[1]
  x <- unclass(get(name, envir = env))
  if (ncol(x) != 6) stop(paste(source_file, "has", ncol(x), "columns, expected 6"))
  out <- as.data.frame(x[, , drop = FALSE])
  colnames(out) <- header
  target <- file.path(args[2], sprintf("adis16405_unit%d.csv", i))
  write.csv(out, target, row.names = FALSE, quote = FALSE)
  cat(target, nrow(out), "rows\n")
}
