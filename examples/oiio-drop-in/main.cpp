// A small renderer that knows only OpenImageIO's TextureSystem: ustring names, TextureOpt, handles
// and per-thread info. It renders a textured plane seen at a grazing angle under a lat-long sky and
// writes the image. Built with FOOTPRINT_DROP_IN, the one line that creates the texture system
// creates footprint's instead; nothing else changes.
//
//   oiio-drop-in-oiio OUT.exr        oiio-drop-in-footprint OUT.exr
#include <Imath/ImathVec.h>  // before OpenImageIO/texture.h
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/texture.h>

#ifdef FOOTPRINT_DROP_IN
#include <footprint/oiio/texture_system.h>
#endif

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

using OIIO::ustring;

// The inputs, made here so that the example needs no files: a checkerboard texture and a sky,
// both written by OpenImageIO's maketx.
static bool make_inputs(const std::string& texture, const std::string& sky) {
    OIIO::ImageBuf checker(OIIO::ImageSpec(512, 512, 3, OIIO::TypeDesc::FLOAT));
    const float dark[3] = {0.05f, 0.05f, 0.08f}, light[3] = {0.9f, 0.85f, 0.7f};
    OIIO::ImageBufAlgo::checker(checker, 16, 16, 1, dark, light);
    OIIO::ImageBuf env(OIIO::ImageSpec(256, 128, 3, OIIO::TypeDesc::FLOAT));
    for (int y = 0; y < 128; ++y)
        for (int x = 0; x < 256; ++x) {
            const float up = 1.0f - static_cast<float>(y) / 128;  // 1 at the zenith
            const float stripe = (x / 16) % 2 ? 1.0f : 0.6f;
            const float rgb[3] = {0.3f * up * stripe, 0.5f * up * stripe, 0.9f * up + 0.1f};
            env.setpixel(x, y, rgb, 3);
        }
    OIIO::ImageSpec config;
    config.attribute("wrapmodes", "periodic,periodic");
    return OIIO::ImageBufAlgo::make_texture(OIIO::ImageBufAlgo::MakeTxTexture, checker, texture,
                                            config) &&
           OIIO::ImageBufAlgo::make_texture(OIIO::ImageBufAlgo::MakeTxEnvLatl, env, sky,
                                            OIIO::ImageSpec());
}

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: %s OUT.exr\n", argv[0]);
        return 2;
    }
    const std::filesystem::path dir = std::filesystem::path(argv[1]).parent_path();
    const std::string texture = (dir / "checker.tx").string(), sky = (dir / "sky.tx").string();
    if (!make_inputs(texture, sky)) {
        std::fprintf(stderr, "cannot make the inputs: %s\n", OIIO::geterror().c_str());
        return 1;
    }

#ifdef FOOTPRINT_DROP_IN
    OIIO::TextureSystem* ts = footprint::oiio::create_texture_system();  // the one line
#else
    OIIO::TextureSystem* ts = OIIO::TextureSystem::create();
#endif

    OIIO::TextureSystem::Perthread* thread = ts->get_perthread_info();
    OIIO::TextureSystem::TextureHandle* plane = ts->get_texture_handle(ustring(texture), thread);
    OIIO::TextureSystem::TextureHandle* env = ts->get_texture_handle(ustring(sky), thread);
    const int width = 320, height = 180;
    OIIO::ImageBuf image(OIIO::ImageSpec(width, height, 3, OIIO::TypeDesc::FLOAT));
    OIIO::TextureOpt options;
    bool ok = true;
    // A pinhole camera 1 unit above the plane y = 0, looking slightly down along −z.
    const float focal = 1.2f, eye_y = 1.0f;
    for (int py = 0; py < height; ++py) {
        for (int px = 0; px < width; ++px) {
            const auto ray = [&](float x, float y) {
                return Imath::V3f((x - 0.5f * width) / height, (0.5f * height - y) / height - 0.15f,
                                  -focal)
                    .normalized();
            };
            const Imath::V3f d = ray(px + 0.5f, py + 0.5f), dx = ray(px + 1.5f, py + 0.5f) - d,
                             dy = ray(px + 0.5f, py + 1.5f) - d;
            float rgb[3];
            if (d.y < -1e-3f) {
                // The plane: (s, t) = (x, z)/4 where the ray meets it, and their differentials.
                const auto hit = [&](const Imath::V3f& r) { return r * (eye_y / -r.y); };
                const Imath::V3f p = hit(d), px1 = hit(d + dx), py1 = hit(d + dy);
                ok &= ts->texture(plane, thread, options, p.x / 4, p.z / 4, (px1.x - p.x) / 4,
                                  (px1.z - p.z) / 4, (py1.x - p.x) / 4, (py1.z - p.z) / 4, 3, rgb);
            } else {
                ok &= ts->environment(env, thread, options, d, dx, dy, 3, rgb);
            }
            image.setpixel(px, py, rgb, 3);
        }
    }
    if (!ok) std::fprintf(stderr, "lookups failed: %s\n", ts->geterror().c_str());
    std::printf("%s", ts->getstats(1, false).substr(0, 400).c_str());

#ifdef FOOTPRINT_DROP_IN
    footprint::oiio::destroy_texture_system(ts);
#else
    OIIO::TextureSystem::destroy(ts);
#endif
    if (!ok || !image.write(argv[1])) {
        std::fprintf(stderr, "failed: %s\n", image.geterror().c_str());
        return 1;
    }
    return 0;
}
