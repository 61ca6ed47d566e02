// oiio/texture_system.h — footprint behind OpenImageIO's TextureSystem interface: a drop-in for
// renderers that call OIIO::TextureSystem (directly, or through OSL's RendererServices).
//
//   #include <footprint/oiio/texture_system.h>
//
//   // was: OIIO::TextureSystem* ts = OIIO::TextureSystem::create();
//   OIIO::TextureSystem* ts = footprint::oiio::create_texture_system();
//   OIIO::TextureOpt opt;
//   float rgb[3];
//   if (!ts->texture(OIIO::ustring("albedo.tx"), opt, s, t, dsdx, dtdx, dsdy, dtdy, 3, rgb))
//       std::cerr << ts->geterror() << "\n";
//   // was: OIIO::TextureSystem::destroy(ts);
//   footprint::oiio::destroy_texture_system(ts);
//
// The object implements every call of OpenImageIO 2.4's TextureSystem. footprint filters the 2D
// texture() and lat-long environment() lookups it can answer — footprint assembly for the default
// (anisotropic) mip mode, OpenImageIO's own closest, bilinear, one-level and trilinear rules for
// the others — and hands everything else (3D textures, shadows, bicubic interpolation, blur in the
// anisotropic mode, cropped or overscanned files, stochastic modes, …) to an OpenImageIO
// TextureSystem it owns, so that no call a host makes breaks. docs/library.md lists, call by call
// and option by option, which is which.
//
// Values are returned as OpenImageIO returns them: as stored (8-bit textures are not decoded from
// sRGB), in OpenImageIO's (s, t) and direction conventions, with its wrap, fill, firstchannel,
// missingcolor and gray_to_rgb rules and maketx's metadata. Hostile arguments (a NaN coordinate, a
// negative width, a subimage or channel out of range, a bad handle) make the call return false
// with a message from geterror() naming the file and the value; they never reach the delegate.
// Thread safety is OpenImageIO's: every call may be made from any number of threads at once.
#pragma once

#include <Imath/ImathVec.h>  // before texture.h, which otherwise forward-declares Imath::V3f
#include <OpenImageIO/texture.h>

#include <string>

#include <footprint/texture_system.h>

namespace footprint::oiio {

// A new texture system: footprint's, with `options` (max_memory_mb bounds footprint's tiles and
// the delegate's cache alike; TextureSystemOptions::color is ignored: values are as stored), or
// null where the options are refused (create_error() says why). OpenImageIO's "max_memory_MB",
// "autotile", "automip", "gray_to_rgb", "flip_t", "latlong_up", … attributes are honoured when
// set through attribute() before the first lookup.
OIIO::TextureSystem* create_texture_system(const TextureSystemOptions& options = {});

// Destroys a texture system made by create_texture_system() (not one of OpenImageIO's).
void destroy_texture_system(OIIO::TextureSystem* system);

// Why the calling thread's last create_texture_system() returned null.
std::string create_error();

}  // namespace footprint::oiio
