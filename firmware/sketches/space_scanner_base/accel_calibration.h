// Accelerometer calibration of the space scanner's MPU6050 (the diploma's ellipsoid model,
// section 3.2: M ~ A m + b, applied as m = A^-1 (M - b) to the reading in m/s^2).
// The identity: no calibration yet. Replace this file with the output of
//   rosrun space_scanner_hw calibrate_accel --bag imu.bag -o accel_calibration.h
// (imu/data_raw recorded at rest in many orientations; see space_scanner_hw/README.md).
#pragma once

// A^-1 (row-major)
const float ACCEL_CAL_MATRIX[3][3] = {
  {1, 0, 0},
  {0, 1, 0},
  {0, 0, 1}
};
// b, m/s^2
const float ACCEL_CAL_OFFSET[3] = {0, 0, 0};
