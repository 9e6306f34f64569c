// map_server's C++ API (navigation 1.17.3, include/map_server/image_loader.h): an image file
// read into a nav_msgs/GetMap response, for C++ programs that link map_server_image_loader.
// The map_server node of this package is Python (src/map_server/map_io.py); both read an image
// the same way, which test/gtest_image_loader.cpp and test/test_map_io.py check on the same
// files.
#ifndef MAP_SERVER_IMAGE_LOADER_H
#define MAP_SERVER_IMAGE_LOADER_H

#include <nav_msgs/GetMap.h>

/** How a pixel becomes a cell (the map YAML's `mode`), p = (255 - mean) / 255 (negated: mean / 255):
 *  TRINARY: p > occ_th -> 100, p < free_th -> 0, otherwise -1 (unknown);
 *  SCALE:   as TRINARY, except that between the thresholds a cell is 1 + 98 (p - free_th) /
 *           (occ_th - free_th), or -1 where the pixel is fully transparent; the mean leaves the
 *           alpha channel out;
 *  RAW:     the mean itself (0..255, stored in the int8 cell). */
enum MapMode
{
  TRINARY,
  SCALE,
  RAW
};

namespace map_server
{

/** Reads the image `fname` (PGM, PNG, BMP, JPEG ... through SDL_image) into resp->map: width and
 *  height of the image, `res` metres per cell, origin (x, y, yaw) of the lower-left pixel
 *  (nullptr: 0, 0, 0), the image's top row as the map's last row.
 *  @throws std::runtime_error naming the file when it cannot be read as an image. */
void loadMapFromFile(nav_msgs::GetMap::Response* resp, const char* fname, double res, bool negate, double occ_th,
                     double free_th, double* origin = nullptr, MapMode mode = TRINARY);

}  // namespace map_server

#endif  // MAP_SERVER_IMAGE_LOADER_H
