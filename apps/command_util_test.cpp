// Tests of contact sheets (command_util.h): the panels are the images' pixels, the labels are
// drawn in the strips under them, and a missing font leaves blank strips and a warning.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "command_util.h"

namespace footprint {
namespace {

// Two distinct 160×90 panels: a horizontal ramp and a vertical one.
std::vector<Image> two_panels() {
    std::vector<Image> images(2, Image(160, 90, 3));
    for (int y = 0; y < 90; ++y)
        for (int x = 0; x < 160; ++x)
            for (int c = 0; c < 3; ++c) {
                images[0].at(x, y, c) = static_cast<float>(x) / 160.0f;
                images[1].at(x, y, c) = static_cast<float>(y) / 90.0f;
            }
    return images;
}

bool panel_is_image(const Image& sheet, const SheetRect& r, const Image& image) {
    for (int y = 0; y < r.height; ++y)
        for (int x = 0; x < r.width; ++x)
            for (int c = 0; c < image.channels; ++c)
                if (sheet.at(r.x + x, r.y + y, c) != image.at(x, y, c)) return false;
    return true;
}

// The strip's pixels with channel 0 above `threshold` (text is white on near black).
int bright_pixels(const Image& sheet, const SheetRect& r, float threshold = 0.5f) {
    int count = 0;
    for (int y = r.y; y < r.y + r.height; ++y)
        for (int x = r.x; x < r.x + r.width; ++x) count += sheet.at(x, y, 0) > threshold;
    return count;
}

std::vector<float> strip_pixels(const Image& sheet, const SheetRect& r) {
    std::vector<float> values;
    for (int y = r.y; y < r.y + r.height; ++y)
        for (int x = r.x; x < r.x + r.width; ++x) values.push_back(sheet.at(x, y, 0));
    return values;
}

TEST(ContactSheet, LabelsAreDrawnUnderUntouchedPanels) {
    const std::vector<Image> images = two_panels();
    const ContactSheet sheet = contact_sheet(
        {&images[0], &images[1]},
        {panel_label("reference", 64, NAN, 0.87), panel_label("fa-rough", 1, 0.2703, 0.031)},
        {2, 4});
    ASSERT_EQ(sheet.warning, "");
    ASSERT_EQ(sheet.panels.size(), 2u);
    ASSERT_EQ(sheet.strips.size(), 2u);
    EXPECT_EQ(sheet.image.width, 2 * 160 + 3 * 4);
    EXPECT_EQ(sheet.image.height, 90 + sheet.strips[0].height + 2 * 4);
    for (int i = 0; i < 2; ++i) {
        EXPECT_TRUE(panel_is_image(sheet.image, sheet.panels[i], images[i])) << i;
        const SheetRect& s = sheet.strips[i];
        EXPECT_EQ(s.y, sheet.panels[i].y + 90) << i;  // directly under its panel
        EXPECT_EQ(s.width, 160);
        constexpr int kLegibleHeight = 12;  // room for a 9-pixel font or larger
        EXPECT_GE(s.height, kLegibleHeight);
        // Text: a good number of white pixels (a single glyph has dozens).
        EXPECT_GT(bright_pixels(sheet.image, s), 100) << i;
    }
    EXPECT_NE(strip_pixels(sheet.image, sheet.strips[0]),
              strip_pixels(sheet.image, sheet.strips[1]));
    // The label's start is in the strip's left part: far more text on the left half.
    SheetRect left = sheet.strips[0], right = sheet.strips[0];
    left.width = right.width = 80;
    right.x += 80;
    EXPECT_GT(bright_pixels(sheet.image, left), bright_pixels(sheet.image, right));
}

// A label too long for its panel at the smallest size (texture-demo --size 160's) stays in its
// strip: the gap and the next panel's strip, left without a label, stay as they were.
TEST(ContactSheet, ALongLabelStaysInItsStrip) {
    const std::vector<Image> images = two_panels();
    const std::string long_label =
        "nearest | 1 spp | RMSE 0.2285 | 0.721 ms | and a good deal more than fits in 160 pixels";
    const ContactSheet sheet = contact_sheet({&images[0], &images[1]}, {long_label, ""}, {2, 4});
    ASSERT_EQ(sheet.warning, "");
    const SheetRect& next = sheet.strips[1];
    EXPECT_EQ(bright_pixels(sheet.image, next, 0.05f), 0);
    const SheetRect gap{sheet.strips[0].x + sheet.strips[0].width, next.y, 4, next.height};
    EXPECT_EQ(bright_pixels(sheet.image, gap), 0);  // grey (0.18) between the panels
    EXPECT_GT(bright_pixels(sheet.image, sheet.strips[0]), 100);
}

TEST(ContactSheet, MissingFontLeavesBlankStripsAndSaysWhy) {
    const std::vector<Image> images = two_panels();
    ContactSheetOptions options;
    options.columns = 2;
    options.font = "/no/such/dir/NoFont.ttf";
    const ContactSheet sheet =
        contact_sheet({&images[0], &images[1]}, {"reference", "point"}, options);
    EXPECT_NE(sheet.warning.find("/no/such/dir/NoFont.ttf"), std::string::npos) << sheet.warning;
    EXPECT_NE(sheet.warning.find("not found"), std::string::npos) << sheet.warning;
    EXPECT_EQ(sheet.warning.find('\n'), std::string::npos) << sheet.warning;
    ASSERT_EQ(sheet.strips.size(), 2u);
    for (int i = 0; i < 2; ++i) {
        EXPECT_TRUE(panel_is_image(sheet.image, sheet.panels[i], images[i])) << i;
        EXPECT_EQ(bright_pixels(sheet.image, sheet.strips[i], 0.05f), 0) << i;
    }
}

TEST(ContactSheet, WithoutLabelsNoStrips) {
    const std::vector<Image> images = two_panels();
    const ContactSheet sheet = contact_sheet({&images[0], &images[1], &images[0]}, {}, {2, 3});
    EXPECT_TRUE(sheet.strips.empty());
    EXPECT_EQ(sheet.warning, "");
    EXPECT_EQ(sheet.image.width, 2 * 160 + 3 * 3);
    EXPECT_EQ(sheet.image.height, 2 * 90 + 3 * 3);
    ASSERT_EQ(sheet.panels.size(), 3u);
    EXPECT_EQ(sheet.panels[2].x, 3);
    EXPECT_EQ(sheet.panels[2].y, 90 + 2 * 3);
    EXPECT_TRUE(panel_is_image(sheet.image, sheet.panels[2], images[0]));
}

TEST(ContactSheet, PanelLabelNamesModeSppRmseAndTime) {
    EXPECT_EQ(panel_label("fa-rough", 1, 0.27031, 0.0312),
              "fa-rough | 1 spp | RMSE "
              "0.2703 | 31.2 ms");
    EXPECT_EQ(panel_label("reference", 64, NAN, 2.5), "reference | 64 spp | 2.5 s");
    // ASCII only: OpenImageIO draws a UTF-8 "·" as two wrong glyphs.
    for (char c : panel_label("ewa-rough", 1, 1e-9, 1234.5))
        EXPECT_LT(static_cast<unsigned char>(c), 0x80u) << c;
}

}  // namespace
}  // namespace footprint
