#include "map_server/image_loader.h"

#include <SDL/SDL_image.h>

#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>

namespace map_server
{

namespace
{

struct SurfaceFree
{
  void operator()(SDL_Surface* s) const { SDL_FreeSurface(s); }
};

// The pixel at (x, y) of a locked surface as r, g, b, a (palettes resolved, any byte order).
void pixelRGBA(const SDL_Surface* img, int x, int y, Uint8 rgba[4])
{
  const int bpp = img->format->BytesPerPixel;
  const Uint8* p = static_cast<const Uint8*>(img->pixels) + y * img->pitch + x * bpp;
  Uint32 v = 0;
  switch (bpp)
  {
    case 1:
      v = *p;
      break;
    case 2:
      v = *reinterpret_cast<const Uint16*>(p);
      break;
    case 3:
      v = SDL_BYTEORDER == SDL_BIG_ENDIAN ? (p[0] << 16 | p[1] << 8 | p[2]) : (p[0] | p[1] << 8 | p[2] << 16);
      break;
    default:
      v = *reinterpret_cast<const Uint32*>(p);
      break;
  }
  SDL_GetRGBA(v, img->format, &rgba[0], &rgba[1], &rgba[2], &rgba[3]);
}

// The cell of one pixel (see MapMode).
int8_t cellOf(const Uint8 rgba[4], bool has_alpha, bool negate, double occ_th, double free_th, MapMode mode)
{
  const int channels = (has_alpha && mode == TRINARY) ? 4 : 3;
  int sum = 0;
  for (int k = 0; k < channels; ++k)
    sum += rgba[k];
  double mean = sum / static_cast<double>(channels);
  if (negate)
    mean = 255.0 - mean;
  if (mode == RAW)
    return static_cast<int8_t>(static_cast<Uint8>(mean));
  const double p = (255.0 - mean) / 255.0;
  if (p > occ_th)
    return 100;
  if (p < free_th)
    return 0;
  if (mode == TRINARY || (has_alpha && rgba[3] == 0))
    return -1;  // unknown, or transparent
  const double span = occ_th - free_th;
  return static_cast<int8_t>(1 + 98 * (span > 0 ? (p - free_th) / span : 0.0));
}

}  // namespace

void loadMapFromFile(nav_msgs::GetMap::Response* resp, const char* fname, double res, bool negate, double occ_th,
                     double free_th, double* origin, MapMode mode)
{
  std::unique_ptr<SDL_Surface, SurfaceFree> img(IMG_Load(fname));
  if (!img)
  {
    throw std::runtime_error(std::string("failed to open image file \"") + fname + "\": " + IMG_GetError());
  }
  const double zero[3] = { 0.0, 0.0, 0.0 };
  const double* o = origin ? origin : zero;
  nav_msgs::MapMetaData& info = resp->map.info;
  info.width = img->w;
  info.height = img->h;
  info.resolution = res;
  info.origin.position.x = o[0];
  info.origin.position.y = o[1];
  info.origin.position.z = 0.0;
  info.origin.orientation.x = 0.0;  // the rotation by yaw about z
  info.origin.orientation.y = 0.0;
  info.origin.orientation.z = std::sin(o[2] / 2.0);
  info.origin.orientation.w = std::cos(o[2] / 2.0);
  resp->map.data.assign(static_cast<size_t>(info.width) * info.height, 0);

  const bool has_alpha = img->format->Amask != 0;
  if (SDL_MUSTLOCK(img.get()))
    SDL_LockSurface(img.get());
  Uint8 rgba[4];
  for (int y = 0; y < img->h; ++y)
  {
    const size_t row = static_cast<size_t>(img->h - 1 - y) * info.width;  // image top = map top
    for (int x = 0; x < img->w; ++x)
    {
      pixelRGBA(img.get(), x, y, rgba);
      resp->map.data[row + x] = cellOf(rgba, has_alpha, negate, occ_th, free_th, mode);
    }
  }
  if (SDL_MUSTLOCK(img.get()))
    SDL_UnlockSurface(img.get());
}

}  // namespace map_server
