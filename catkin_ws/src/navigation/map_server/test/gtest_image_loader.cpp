// map_server::loadMapFromFile (include/map_server/image_loader.h) on the test images of
// make_fixtures.py: navigation's 10 x 10 test map as PNG and BMP, a missing file, and an RGBA ramp
// in every mode, cell for cell as map_io.py (the Python node's loader) reads the same file.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "map_server/image_loader.h"

namespace
{

const std::string kDir = MAP_SERVER_TEST_DIR;

// the test map, bottom row first (an OccupancyGrid's order)
const std::vector<int> kTestMap = { 0,   0,   0,   0,   0, 0, 0,   0,   0,   0,  //
                                    100, 100, 100, 100, 0, 0, 100, 100, 100, 0,  //
                                    100, 100, 100, 100, 0, 0, 100, 100, 100, 0,  //
                                    100, 0,   0,   0,   0, 0, 0,   0,   0,   0,  //
                                    100, 0,   0,   0,   0, 0, 0,   0,   0,   0,  //
                                    100, 0,   0,   0,   0, 0, 100, 100, 0,   0,  //
                                    100, 0,   0,   0,   0, 0, 100, 100, 0,   0,  //
                                    100, 0,   0,   0,   0, 0, 100, 100, 0,   0,  //
                                    100, 0,   0,   0,   0, 0, 100, 100, 0,   0,  //
                                    100, 0,   0,   0,   0, 0, 0,   0,   0,   0 };

std::vector<int> cells(const nav_msgs::GetMap::Response& resp)
{
  return std::vector<int>(resp.map.data.begin(), resp.map.data.end());
}

std::vector<int> readCells(const std::string& path)
{
  std::ifstream in(path);
  std::vector<int> out;
  int v;
  while (in >> v)
    out.push_back(v);
  return out;
}

void expectTestMap(const char* file)
{
  nav_msgs::GetMap::Response resp;
  double origin[3] = { -1.0, 2.0, 0.0 };
  map_server::loadMapFromFile(&resp, (kDir + "/" + file).c_str(), 0.1, false, 0.65, 0.1, origin);
  EXPECT_FLOAT_EQ(resp.map.info.resolution, 0.1f);
  EXPECT_EQ(resp.map.info.width, 10u);
  EXPECT_EQ(resp.map.info.height, 10u);
  EXPECT_DOUBLE_EQ(resp.map.info.origin.position.x, -1.0);
  EXPECT_DOUBLE_EQ(resp.map.info.origin.position.y, 2.0);
  EXPECT_DOUBLE_EQ(resp.map.info.origin.orientation.w, 1.0);
  EXPECT_EQ(cells(resp), kTestMap);
}

}  // namespace

TEST(MapServer, loadValidPNG) { expectTestMap("testmap.png"); }

TEST(MapServer, loadValidBMP) { expectTestMap("testmap.bmp"); }

TEST(MapServer, loadInvalidFile)
{
  nav_msgs::GetMap::Response resp;
  double origin[3] = { 0.0, 0.0, 0.0 };
  try
  {
    map_server::loadMapFromFile(&resp, "foo", 0.1, false, 0.65, 0.1, origin);
    ADD_FAILURE() << "no exception for a missing file";
  }
  catch (const std::runtime_error& e)
  {
    EXPECT_EQ(std::string(e.what()).rfind("failed to open image file \"foo\"", 0), 0u) << e.what();
  }
}

TEST(MapServer, originYawAndNoOrigin)
{
  nav_msgs::GetMap::Response resp;
  double origin[3] = { 0.5, -0.5, 1.2 };
  const std::string png = kDir + "/testmap.png";
  map_server::loadMapFromFile(&resp, png.c_str(), 0.05, false, 0.65, 0.196, origin);
  EXPECT_NEAR(resp.map.info.origin.orientation.z, std::sin(0.6), 1e-12);
  EXPECT_NEAR(resp.map.info.origin.orientation.w, std::cos(0.6), 1e-12);
  nav_msgs::GetMap::Response plain;  // the older call without an origin: 0, 0, 0
  map_server::loadMapFromFile(&plain, png.c_str(), 0.05, false, 0.65, 0.196);
  EXPECT_EQ(plain.map.info.origin.position.x, 0.0);
  EXPECT_EQ(plain.map.info.origin.orientation.w, 1.0);
  EXPECT_EQ(cells(plain), kTestMap);
}

// every mode of the RGBA ramp: the same cells as the Python loader (spectrum_<mode>.txt)
TEST(MapServer, everyModeAsThePythonLoader)
{
  struct Case
  {
    const char* name;
    MapMode mode;
    bool negate;
  };
  const std::string png = kDir + "/spectrum.png";
  for (const Case& c : { Case{ "trinary", TRINARY, false }, Case{ "scale", SCALE, false }, Case{ "raw", RAW, false },
                         Case{ "negate", TRINARY, true } })
  {
    nav_msgs::GetMap::Response resp;
    double origin[3] = { 0.0, 0.0, 0.0 };
    map_server::loadMapFromFile(&resp, png.c_str(), 0.05, c.negate, 0.65, 0.196, origin, c.mode);
    EXPECT_EQ(resp.map.info.width, 32u);
    EXPECT_EQ(resp.map.info.height, 4u);
    EXPECT_EQ(cells(resp), readCells(kDir + "/spectrum_" + c.name + ".txt")) << c.name;
  }
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
